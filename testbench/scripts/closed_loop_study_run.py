#!/usr/bin/python3
"""scripts/closed_loop_study.py end to end on the bundled bunny at a small size with
two methods: the page, the charts, the replay check, and figures that agree with
vbsim's own stats files.

    /usr/bin/python3 closed_loop_study_run.py PATH_TO_VBSIM
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SCRIPT = os.path.join(ROOT, "scripts", "closed_loop_study.py")
BUNNY = os.path.join(ROOT, "traces", "bunny", "bunny.obj")
VBSIM = None


class ClosedLoopStudyTest(unittest.TestCase):
    def test_page_and_figures(self):
        with tempfile.TemporaryDirectory() as tmp:
            work, out = os.path.join(tmp, "work"), os.path.join(tmp, "out")
            r = subprocess.run(["/usr/bin/python3", SCRIPT, BUNNY, "--vbsim", VBSIM, "--methods", "none,validity-bit",
                                "--size", "32x24", "--spp", "1", "--work", work, "--out", out],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            for name in ("closed-loop.md", "closed-loop.png", "closed-loop-montage.png"):
                self.assertTrue(os.path.getsize(os.path.join(out, name)) > 0, name)
            page = open(os.path.join(out, "closed-loop.md")).read()
            # Each row holds the figures of the two stats files the script read.
            for method in ("none", "validity-bit"):
                ref = json.load(open(os.path.join(work, f"bunny-{method}-exact.json")))
                loop = json.load(open(os.path.join(work, f"bunny-{method}-method.json")))
                row = next(line for line in page.splitlines() if line.startswith(f"| {method} |"))
                cells = [c.strip() for c in row.strip("|").split("|")]
                self.assertEqual(cells[1], f"{ref['rays']:,}")
                self.assertEqual(cells[2], f"{loop['rays']:,}")
                self.assertEqual(cells[3], f"{ref['hw']['cycles']:,}")
                self.assertEqual(cells[4], f"{loop['hw']['cycles']:,}")
                self.assertEqual(cells[10], f"{ref['pixels']['acne']:,}")
                self.assertEqual(cells[11], f"{loop['pixels']['acne']:,}")
                # The reference rays are the same for every method; the exact image too.
                self.assertEqual(ref["rays"], json.load(open(os.path.join(work, "bunny-none-exact.json")))["rays"])
            # The replay check: the reference trace replayed gives the render's cycles.
            check = re.search(r"\| `bunny-reference.jsonl` \| none \| ([\d,]+) \| ([\d,]+) \|", page)
            self.assertIsNotNone(check, page)
            self.assertEqual(check.group(1), check.group(2))
            replay = json.load(open(os.path.join(work, "bunny-reference.jsonl.none.replay.json")))
            self.assertEqual(f"{replay['hw']['cycles']:,}", check.group(1))
            # `none` re-hits its surfaces: acne in both runs.
            none_ref = json.load(open(os.path.join(work, "bunny-none-exact.json")))
            self.assertGreater(none_ref["pixels"]["acne"], 0)

    def test_unknown_scene_is_an_error(self):
        with tempfile.TemporaryDirectory() as tmp:
            r = subprocess.run(["/usr/bin/python3", SCRIPT, "no-such-scenario", "--vbsim", VBSIM, "--work", tmp,
                                "--out", tmp], capture_output=True, text=True)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("no-such-scenario", r.stdout + r.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "closed-loop.md")))


if __name__ == "__main__":
    VBSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
