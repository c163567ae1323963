#!/usr/bin/python3
"""Progress on a terminal: replay (both modes), oracle, score and gen draw a
line with percentage and time left on stderr when it is a terminal (a pty
here), and print none of it when stderr is a pipe or -q is given.

    /usr/bin/python3 cli_progress_run.py PATH_TO_VBSIM
"""
import os
import random
import re
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
VBSIM = None
# Sized for runs well beyond the first redraw (200 ms) on a fast machine: the
# functional replay and score take about 2 us a ray, the cycle-level replay
# about 2.5 us (120,000 rays finished in 0.3 s, too close to the first redraw),
# the exact oracle 15 us.
BIG, SMALL = 500000, 120000


def camera_trace(path, rays):
    """Camera rays from in front of the bunny toward it."""
    rng = random.Random(7)
    with open(path, "w") as f:
        bunny = os.path.abspath(os.path.join(ROOT, "traces", "bunny", "bunny.obj"))
        f.write('{"format":"vbsim-trace","version":1,"scene":"%s"}\n' % bunny)
        for i in range(rays):
            f.write('{"id":%d,"o":[0,5,20],"d":[%.4f,%.4f,-20]}\n' % (i, rng.uniform(-5, 5), rng.uniform(-5, 5)))


def on_terminal(args):
    """Runs vbsim with stderr on a pseudo-terminal; (exit code, stdout, what the terminal showed)."""
    master, slave = os.openpty()
    proc = subprocess.Popen([VBSIM, *args], stdout=subprocess.PIPE, stderr=slave)
    os.close(slave)
    shown = b""
    while True:
        try:
            block = os.read(master, 4096)
        except OSError:  # EIO: the child closed the terminal
            break
        if not block:
            break
        shown += block
    out = proc.stdout.read()
    proc.stdout.close()
    proc.wait()
    os.close(master)
    return proc.returncode, out.decode(), shown.decode(errors="replace")


class ProgressTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.trace = os.path.join(cls.tmp.name, "big.jsonl")
        camera_trace(cls.trace, BIG)
        cls.small = os.path.join(cls.tmp.name, "small.jsonl")
        camera_trace(cls.small, SMALL)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def check_line(self, args, label, total, unit="rays", piped_too=False):
        code, out, shown = on_terminal(args)
        self.assertEqual(code, 0, shown)
        # "\rLABEL   12.3%  24576/200000 rays  ...  ETA 0:01", then cleared.
        pattern = r"\r" + re.escape(label) + r" +\d+\.\d%  \d+/" + str(total) + " " + unit + r"  \d+ " + unit + \
            r"/s  ETA \d+:\d\d"
        self.assertRegex(shown, pattern)
        self.assertNotIn("ETA", out)  # never into the data
        if piped_too:
            piped = subprocess.run([VBSIM, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            self.assertNotIn("ETA", piped.stderr)  # not a terminal: no progress line
            self.assertNotIn("%", piped.stderr)
            code, _, shown = on_terminal([*args, "-q"])
            self.assertEqual((code, shown), (0, ""))  # -q: nothing, even on a terminal

    def test_replay_in_both_modes(self):
        self.check_line(["replay", self.trace], "replay (functional)", BIG, piped_too=True)
        self.check_line(["replay", self.trace, "--mode", "cycle"], "replay (cycle)", BIG)

    def test_oracle(self):
        self.check_line(["oracle", self.small, "-o", os.path.join(self.tmp.name, "o.jsonl")], "oracle", SMALL)

    def test_score(self):
        self.check_line(["score", self.trace, "--threads", "1", "--methods", "none,tmin,primid", "--testers",
                         "three-half-plane,moller-trumbore"], "score: 6 configurations", BIG)

    def test_gen(self):
        out = os.path.join(self.tmp.name, "gen")
        code, _, shown = on_terminal(["gen", "paths", "--rays", "20000", "-o", out])
        self.assertEqual(code, 0, shown)
        total = re.search(r"(\d+) rays -> ", shown)
        self.assertIsNotNone(total, shown)
        self.assertRegex(shown, r"\rgen: oracle +\d+\.\d%  \d+/" + total.group(1) + r" rays .* ETA \d+:\d\d")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: cli_progress_run.py PATH_TO_VBSIM")
    VBSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
