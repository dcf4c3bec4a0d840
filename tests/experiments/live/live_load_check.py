"""`drapelab live` under many connections (docs/live.md, "Many connections").

`fig2_hold.json --live-hands`: once the helper's own stream has a frame, 200 raw sockets ask for
GET /events and 100 more connect and send nothing. The server streams to at most 16 pages: 15
of the 200 get frames, the other 185 a 503 that names the limit and the connection closed, at
once. Meanwhile POST /key and POST /hand, each on a new connection, answer within 100 ms every
time (the latency the person driving the run sees; 10 of each, the largest asserted), every
key's event reaches the run (GET /event-log, then summary.json) and the last posted hand is in
the frames. With one stream closed a new one is served. SIGINT ends the others with the run's
last frame and the closing chunk, and the command at once with exit 0 and its files. A stream
whose reader lags when the run stops ends so too.
Usage: live_load_check.py DRAPELAB SOURCE_DIR WORK_DIR
"""
import http.client
import json
import os
import pathlib
import selectors
import socket
import sys
import threading
import time
import urllib.request

from live_client import LiveRun, check_arguments

STREAMS = 16  # max_event_streams, experiments/live/live_command.cpp
OPENED = 200  # event streams asked for
IDLE = 100  # connections that send nothing
ROUNDS = 10  # POST /key and POST /hand, each
LATENCY = 0.1  # s: what a person driving the run may wait for an answer


class Streams:
    """Raw sockets asking for GET /events, read on one thread: each socket's first and last
    bytes and whether it was closed."""

    def __init__(self, port, count):
        self.heads = [b""] * count
        self.tails = [b""] * count
        self.closed = [False] * count
        self.lock = threading.Lock()
        self.selector = selectors.DefaultSelector()
        self.sockets = []
        request = f"GET /events HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode()
        for i in range(count):
            s = socket.create_connection(("127.0.0.1", port), timeout=10)
            s.sendall(request)
            s.setblocking(False)
            self.selector.register(s, selectors.EVENT_READ, i)
            self.sockets.append(s)
        self.running = True
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        while self.running:
            for key, _ in self.selector.select(timeout=0.05):
                try:
                    data = key.fileobj.recv(1 << 16)
                except (BlockingIOError, ConnectionError):
                    continue
                if not data:
                    self.selector.unregister(key.fileobj)
                    with self.lock:
                        self.closed[key.data] = True
                    continue
                with self.lock:
                    if len(self.heads[key.data]) < 4096:
                        self.heads[key.data] += data
                    self.tails[key.data] = (self.tails[key.data] + data)[-(1 << 16):]

    def answered(self):
        """Each socket's head once every one has a frame or has been answered and closed."""
        with self.lock:
            heads, closed = list(self.heads), list(self.closed)
        done = all(c or b"data: {" in h for h, c in zip(heads, closed))
        return heads if done else None

    def wait_closed(self, which, what):
        """The last bytes of the sockets `which` once every one of them is closed."""
        end = time.monotonic() + 10
        while True:
            with self.lock:
                if all(self.closed[i] for i in which):
                    return [self.tails[i] for i in which]
            assert time.monotonic() < end, f"timed out waiting for {what}"
            time.sleep(0.02)

    def close(self):
        self.running = False
        self.reader.join()
        for s in self.sockets:
            s.close()


def timed_post(port, path, body):
    """(seconds, status, text) of POST path on a new connection, connecting included."""
    start = time.monotonic()
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    connection.request("POST", path, body=body.encode())
    response = connection.getresponse()
    text = response.read().decode()
    seconds = time.monotonic() - start
    connection.close()
    return seconds, response.status, text


def check_streams(streams):
    end = time.monotonic() + 10
    while (heads := streams.answered()) is None:
        assert time.monotonic() < end, "not every stream was answered within 10 s"
        time.sleep(0.05)
    served = [h for h in heads if h.startswith(b"HTTP/1.1 200")]
    refused = [h for h in heads if h.startswith(b"HTTP/1.1 503")]
    # the helper's own reader holds the 16th stream
    assert len(served) == STREAMS - 1 and len(refused) == OPENED - STREAMS + 1, \
        (len(served), len(refused))
    assert all(b"text/event-stream" in h for h in served)
    assert all(b"Connection: close" in h for h in refused), refused[0]
    says = f"too many event streams: at most {STREAMS} pages may watch this run at once"
    assert all(says.encode() in h for h in refused), refused[0]
    print(f"{len(served)} streams served, {len(refused)} refused: {says}")
    return [i for i, h in enumerate(heads) if h.startswith(b"HTTP/1.1 200")]


def check_control(run):
    """The largest latency of POST /key and of POST /hand over ROUNDS each; the keys' events."""
    keys, hands = [], []
    for k in range(ROUNDS):
        seconds, status, text = timed_post(run.port, "/key", "m")
        assert (status, text) == (200, "ok\n"), (status, text)
        keys.append(seconds)
        hand = {"x": 0.01 * k, "y": 0.95, "z": 0.40}
        seconds, status, text = timed_post(run.port, "/hand", json.dumps(hand))
        assert (status, text) == (200, "ok\n"), (status, text)
        hands.append(seconds)
        time.sleep(0.02)
    print(f"POST /key: {1e3 * max(keys):.1f} ms at most, POST /hand: {1e3 * max(hands):.1f} ms at "
          f"most ({ROUNDS} each, {OPENED} streams asked for, {IDLE} idle connections)")
    assert max(keys) < LATENCY and max(hands) < LATENCY, (keys, hands)
    # every key reaches the run: its map event, in the server's list of the run's events
    end = time.monotonic() + 10
    while True:
        with urllib.request.urlopen(run.url + "/event-log", timeout=10) as response:
            log = json.loads(response.read())
        maps = [e for e in log if e.get("key") == "m"]
        if len(maps) == ROUNDS:
            break
        assert time.monotonic() < end, log
        time.sleep(0.05)
    # and the last hand posted is where the run has the right hand
    last = (0.01 * (ROUNDS - 1), 0.95, 0.40)
    run.wait_for(lambda f: any(h["hand"] == "right" and h["available"] and
                               all(abs(a - b) <= 1e-12 for a, b in zip(h["position"], last))
                               for h in f["hands"]), "the last posted hand", timeout=10)


def cpu_seconds(pid):
    """User and system CPU time of process pid so far (proc(5): /proc/PID/stat fields 14, 15)."""
    fields = pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def check_stream_again(port):
    """A stream is served once one of the others is closed (the server sees a closed one at its
    next frame, 1/30 s later)."""
    end = time.monotonic() + 5
    while True:
        with socket.create_connection(("127.0.0.1", port), timeout=10) as s:
            s.sendall(f"GET /events HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode())
            head = b""
            while b"\r\n" not in head and (data := s.recv(4096)):
                head += data
        if head.startswith(b"HTTP/1.1 200"):
            return
        assert time.monotonic() < end, head
        time.sleep(0.1)


def check_slow_reader(drapelab, scene, work):
    """A stream whose reader lags (its socket's buffers full when the run stops) still ends
    with the run's last frame and the closing chunk: the server stops once its streams ended."""
    with LiveRun(drapelab, scene, work / "slow_reader", "--live-hands", "--set", "duration=60",
                 "--set", "cloth.rows=100", "--set", "cloth.cols=100") as run:
        run.wait_for(lambda f: True, "the first frame")
        with socket.socket() as slow:
            slow.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
            slow.connect(("127.0.0.1", run.port))
            slow.sendall(f"GET /events HTTP/1.1\r\nHost: 127.0.0.1:{run.port}\r\n\r\n".encode())
            # 100 x 100 frames of 0.16 MB, 30 a second, fill the buffers (the sender's 4 MiB at
            # most, tcp(7) tcp_wmem) within the second: the server's write waits for the reader
            time.sleep(1.5)
            received = []

            def read_late():
                time.sleep(0.3)
                slow.settimeout(10)
                data = b""
                while chunk := slow.recv(1 << 20):
                    data += chunk
                received.append(data)

            reader = threading.Thread(target=read_late)
            reader.start()
            code, _, stderr = run.stop()
            reader.join()
    assert code == 0, (code, stderr)
    data = received[0]
    assert data.endswith(b"\r\n0\r\n\r\n") and \
        b'"status":"stopped"' in data.rsplit(b"data: ", 1)[1], data[-200:]
    print(f"a slow reader: {len(data) / 1e6:.1f} MB, ending with the run's last frame and the "
          f"closing chunk")


def main():
    drapelab, source, work = check_arguments(sys.argv)
    scene = source / "experiments/scenes/fig2_hold.json"
    out = work / "live"
    with LiveRun(drapelab, scene, out, "--live-hands", "--set", "duration=60") as run:
        run.wait_for(lambda f: True, "the first frame")
        streams = Streams(run.port, OPENED)
        idle = [socket.create_connection(("127.0.0.1", run.port), timeout=10) for _ in range(IDLE)]
        served = check_streams(streams)
        # what the open connections cost the cores the simulation runs on (printed only)
        cpu = cpu_seconds(run.proc.pid)
        time.sleep(1.0)
        print(f"drapelab live's CPU with them open: {cpu_seconds(run.proc.pid) - cpu:.2f} s a "
              f"second (the simulation's included)")
        check_control(run)
        for s in idle:
            s.close()
        streams.sockets[served[0]].shutdown(socket.SHUT_RDWR)
        streams.wait_closed(served[:1], "the stream closed")
        check_stream_again(run.port)
        # the streams still open end with the run: the last frame says how, then the closing
        # chunk (without it a browser reports ERR_INCOMPLETE_CHUNKED_ENCODING)
        start = time.monotonic()
        code, stdout, stderr = run.stop()
        seconds = time.monotonic() - start
        tails = streams.wait_closed(served[1:], "the streams' ends")
        streams.close()
        ended = b'"status":"stopped"'
        assert all(t.endswith(b"\r\n0\r\n\r\n") and ended in t.rsplit(b"data: ", 1)[1]
                   for t in tails), [t[-200:] for t in tails]
        assert code == 0, (code, stdout, stderr)
        assert "still holds a request open" not in stderr, stderr
        assert seconds < 5, f"SIGINT took {seconds:.1f} s to end the command"
        summary = json.loads((out / "summary.json").read_text())
        assert summary["status"] == "stopped", summary["status"]
        maps = [e for e in summary["events"] if e.get("key") == "m"]
        assert len(maps) == ROUNDS, summary["events"]
        print(f"stopped in {seconds:.2f} s, {len(tails)} streams ended with the run's last frame; "
              f"summary.json has the {ROUNDS} keys' events")
    check_slow_reader(drapelab, scene, work)


if __name__ == "__main__":
    main()
