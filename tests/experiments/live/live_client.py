"""Helpers shared by the live mode's checks: a free port, a `drapelab live` process, its frames.

The frames are GET /events's server-sent events (docs/live.md), read on a thread so that a check
can wait for a condition on the latest frame with a time limit.
"""
import json
import pathlib
import shutil
import socket
import subprocess
import threading
import time
import urllib.error
import urllib.request


def check_arguments(argv):
    """(DRAPELAB, SOURCE_DIR, WORK_DIR) of a check's command line, WORK_DIR emptied."""
    drapelab, source, work = argv[1], pathlib.Path(argv[2]), pathlib.Path(argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    return drapelab, source, work


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class LiveRun:
    """`drapelab live SCENE --port P --out OUT ARGS...`, started and listening."""

    def __init__(self, drapelab, scene, out, *args):
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.proc = subprocess.Popen([drapelab, "live", str(scene), "--port", str(self.port),
                                      "--out", str(out), *map(str, args)],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.banner = self.proc.stdout.readline()  # the server is listening once this is out
        self.frames = []
        self.lock = threading.Lock()
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        with urllib.request.urlopen(self.url + "/events", timeout=30) as events:
            for raw in events:
                line = raw.decode()
                if line.startswith("data: "):
                    with self.lock:
                        self.frames.append(json.loads(line[6:]))

    def latest(self):
        with self.lock:
            return self.frames[-1] if self.frames else None

    def wait_for(self, condition, what, timeout=30.0):
        """The first frame (from now on) for which condition(frame) holds."""
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            frame = self.latest()
            if frame is not None and condition(frame):
                return frame
            time.sleep(0.02)
        raise AssertionError(f"timed out waiting for {what}; last frame t = "
                             f"{(self.latest() or {}).get('t')}")

    def post(self, path, body):
        """(status, text) of POST path."""
        data = body if isinstance(body, bytes) else body.encode()
        request = urllib.request.Request(self.url + path, data=data, method="POST")
        try:
            with urllib.request.urlopen(request, timeout=10) as response:
                return response.status, response.read().decode()
        except urllib.error.HTTPError as e:
            return e.code, e.read().decode()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.proc.poll() is None:  # a check failed before stop(): leave no server behind
            self.proc.kill()
            self.proc.communicate()

    def stop(self):
        """SIGINT, as Ctrl-C; returns (exit status, the rest of stdout, stderr)."""
        self.proc.send_signal(2)
        out, err = self.proc.communicate(timeout=60)
        return self.proc.returncode, out, err


def replay_events(drapelab, out, replay):
    """The events of `drapelab run OUT/scene.json --out REPLAY`."""
    subprocess.run([drapelab, "run", str(out / "scene.json"), "--out", str(replay), "-q",
                    "--overwrite"], check=True)
    return json.loads((replay / "summary.json").read_text())["events"]
