"""One run's MP4 (drapeanalysis/animation.py, docs/analysis.md): the trace's frames thinned
evenly to max_frames at the given rate, and ffmpeg's failures said in its own words or,
killed by a file size limit, as the failed write it is."""
import errno
import json
import os
import shutil
import signal
import subprocess
import unittest

import numpy as np

import runfolder
from drapeanalysis import animation


class FfmpegFailureTest(unittest.TestCase):
    def test_a_file_size_limit_is_a_failed_write(self):
        error = subprocess.CalledProcessError(-signal.SIGXFSZ, ["ffmpeg"], stderr="frame= 3")
        self.assertEqual(animation.ffmpeg_failure(error),
                         f"{os.strerror(errno.EFBIG)} (ffmpeg stopped by SIGXFSZ)")

    def test_other_failures_say_ffmpegs_last_line_or_its_status(self):
        error = subprocess.CalledProcessError(1, ["ffmpeg"], stderr="Input #0\nout.mp4: No space left on device\n")
        self.assertEqual(animation.ffmpeg_failure(error), "ffmpeg failed (out.mp4: No space left on device)")
        self.assertEqual(animation.ffmpeg_failure(subprocess.CalledProcessError(3, ["ffmpeg"])),
                         "ffmpeg failed (exit 3)")


@unittest.skipUnless(animation.available() and shutil.which("ffprobe"), "needs ffmpeg and ffprobe")
class AnimateRunTest(runfolder.RunFolderTest):
    def frames_and_rate(self, movie):
        done = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
                               "-show_entries", "stream=nb_read_frames,r_frame_rate", "-of", "json", str(movie)],
                              capture_output=True, text=True, check=True, timeout=60)
        stream = json.loads(done.stdout)["streams"][0]
        return int(stream["nb_read_frames"]), stream["r_frame_rate"]

    def test_frames_are_thinned_to_the_limit_at_the_rate_asked(self):
        run = self.make_run()
        t = np.arange(12) * 0.01
        x = np.array([[0.0, 1.0, 0.0], [0.02, 1.0, 0.0], [0.0, 0.98, 0.0], [0.02, 0.98, 0.0]])
        runfolder.write_summary(run, [{"t": 0.05, "type": "hold"}], {"cloth": {"rows": 2, "cols": 2}}, sim_time=0.11)
        runfolder.write_trace(run, t, x[None] + 0.001 * t[:, None, None])
        out = self.directory / "a.mp4"
        self.assertEqual(animation.animate_run(run, out, max_frames=5, fps=10), out)
        self.assertEqual(self.frames_and_rate(out), (5, "10/1"))


if __name__ == "__main__":
    unittest.main()
