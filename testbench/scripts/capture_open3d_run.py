#!/usr/bin/python3
"""vbsim capture of Open3D's RaycastingScene (testbench/capture/open3d_raycast.py,
Debian's python3-open3d: `scripts/setup.sh --open3d`) run by Python, which
loads Open3D's module, and with it libembree3, as a local library: the capture
holds every ray and the bunny's triangles. Open3D passes ray mask 0 and
Debian's Embree honours ray masks, so Embree tests no geometry for any ray
(Open3D reports no hit): the trace declares ray masks (`triangle_masks`, every
ray's `mask` 0), no ray is marked, and the replay and the exact answer honour
the masks: no hit, as Open3D found, while the same rays with all bits hit the
bunny.
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

    def test_every_ray_captured_with_its_mask(self):
        r, out, answer = self.capture("masked")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertEqual(json.load(open(answer)), {"rays": WIDTH * HEIGHT, "hits": 0})
        report = json.load(open(os.path.join(out, "capture.json")))
        self.assertEqual(report["rays_in_trace"], WIDTH * HEIGHT)
        self.assertEqual(report["scene"]["triangles"], 3674)
        self.assertTrue(report["incomplete"]["embree_ray_masks"])
        self.assertEqual(report["incomplete"]["by_reason"], {})
        self.assertEqual(report["masks"], {"declared": True, "triangle_ranges": 0, "rays_with_masks": WIDTH * HEIGHT})
        trace = os.path.join(out, "trace.jsonl")
        lines = open(trace).read().splitlines()
        self.assertEqual(json.loads(lines[0])["triangle_masks"], [])
        rays = [json.loads(line) for line in lines[1:]]
        self.assertTrue(all(ray["mask"] == 0 for ray in rays))
        # The exact answers honour the masks: every ray misses, as Open3D reported.
        scored = os.path.join(self.dir, "scored.jsonl")
        self.assertEqual(run("oracle", "-q", trace, "-o", scored).returncode, 0)
        expects = [json.loads(line)["expect"]["prim"] for line in open(scored).read().splitlines()[1:]]
        self.assertEqual(expects, [-1] * len(rays))
        stats = os.path.join(self.dir, "stats.json")
        hits = os.path.join(self.dir, "replay.hits")
        r = run("replay", "-q", scored, "--method", "validity-bit", "--stats", stats, "--hits", hits)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        total = json.load(open(stats))
        self.assertEqual(total["hits"], 0)
        self.assertEqual(total["verdicts"]["correct"], WIDTH * HEIGHT)
        self.assertGreater(total["avoidance"]["rejected_by"]["mask"], 0)
        r = run("compare-reference", "-q", hits, os.path.join(out, "embree_hits.jsonl"))
        self.assertEqual(r.stdout.strip(), "", "the replay differs from Open3D's own answers")
        # Without the masks (every ray all bits) the same rays meet the bunny.
        unmasked = os.path.join(self.dir, "unmasked.jsonl")
        with open(unmasked, "w") as f:
            header = json.loads(lines[0])
            header["scene"] = os.path.join(out, header["scene"])
            del header["triangle_masks"]
            del header["reference"]
            f.write(json.dumps(header) + "\n")
            for ray in rays:
                ray.pop("mask")
                ray.pop("reference", None)
                f.write(json.dumps(ray) + "\n")
        stats = os.path.join(self.dir, "unmasked.json")
        self.assertEqual(run("replay", "-q", unmasked, "--stats", stats).returncode, 0)
        self.assertGreater(json.load(open(stats))["hits"], WIDTH * HEIGHT // 4)


if __name__ == "__main__":
    if subprocess.run(["/usr/bin/python3", "-c", "import open3d"], capture_output=True).returncode != 0:
        print("Open3D is not installed (scripts/setup.sh --open3d): skipped")
        sys.exit(77)
    VBSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
