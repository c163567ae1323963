#!/usr/bin/python3
"""vbsim capture of Open3D's RaycastingScene (testbench/capture/open3d_raycast.py,
Debian's python3-open3d: `scripts/setup.sh --open3d`) run by Python, which
loads Open3D's module, and with it libembree3, as a local library: the capture
holds every ray and the bunny's triangles. Open3D passes ray mask 0 and
Debian's Embree honours ray masks, so Embree tests no geometry for any ray
(Open3D reports no hit): every ray is marked `mask`, capture exits 1 unless
--allow-partial, and the rays replay and score with --score-incomplete.
Exits 77 (skipped) when Open3D is not installed.

    /usr/bin/python3 capture_open3d_run.py PATH_TO_VBSIM
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
APP = os.path.join(ROOT, "testbench", "capture", "open3d_raycast.py")
BUNNY = os.path.join(ROOT, "traces", "bunny", "bunny.obj")
VBSIM = None
WIDTH, HEIGHT = 32, 24


def run(*args):
    return subprocess.run([VBSIM, *args], capture_output=True, text=True)


class CaptureOpen3dTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = cls.tmp.name

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def capture(self, name, *options):
        out = os.path.join(self.dir, name)
        answer = os.path.join(self.dir, name + ".json")
        r = run("capture", *options, "-o", out, "--", "/usr/bin/python3", APP, BUNNY, answer, str(WIDTH),
                str(HEIGHT))
        return r, out, answer

    def test_every_ray_captured_and_marked_mask(self):
        r, out, answer = self.capture("partial", "--allow-partial")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertEqual(json.load(open(answer)), {"rays": WIDTH * HEIGHT, "hits": 0})
        report = json.load(open(os.path.join(out, "capture.json")))
        self.assertEqual(report["rays_in_trace"], WIDTH * HEIGHT)
        self.assertEqual(report["scene"]["triangles"], 3674)
        self.assertTrue(report["incomplete"]["embree_ray_masks"])
        self.assertEqual(report["incomplete"]["by_reason"], {"mask": WIDTH * HEIGHT})
        scored = os.path.join(self.dir, "scored.jsonl")
        self.assertEqual(run("oracle", "-q", os.path.join(out, "trace.jsonl"), "-o", scored).returncode, 0)
        stats = os.path.join(self.dir, "stats.json")
        r = run("replay", "-q", scored, "--method", "validity-bit", "--score-incomplete", "--stats", stats)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("validity-bit", open(stats).read())

    def test_refused_without_allow_partial(self):
        r, out, _ = self.capture("strict")
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn("incomplete", r.stderr)
        self.assertNotIn("Aborted", r.stderr)


if __name__ == "__main__":
    if subprocess.run(["/usr/bin/python3", "-c", "import open3d"], capture_output=True).returncode != 0:
        print("Open3D is not installed (scripts/setup.sh --open3d): skipped")
        sys.exit(77)
    VBSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
