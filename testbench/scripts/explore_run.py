#!/usr/bin/python3
"""Runs `vbsim explore` end to end on a tiny definition (the bundled paths
trace through the oracle, a generated scenario; two methods; two designs) and
checks what it writes: points.csv's rows and columns, the area the shared
avoidance units save, errors that do not depend on the design, report.md and
its charts, a rerun that takes every point from the cache, and a bad
definition refused with the file and the field named.

    /usr/bin/python3 explore_run.py PATH_TO_VBSIM
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
VBSIM = None

DEFINITION = {
    "name": "tiny",
    "preset": "small",
    "workloads": [{"name": "paths", "trace": os.path.join(os.path.abspath(ROOT), "traces/bunny/paths.jsonl"),
                   "oracle": True},
                  {"name": "nested", "scenario": "layers", "pick": "layers-nested-spheres", "rays": 200, "seed": 3}],
    "methods": ["primid", {"name": "validity-bit (vote)", "method": "validity-bit:vb-policy=vote"}],
    "designs": {"grid": {"avoidance.share": [1, 2]}},
}


def explore(definition_path, out):
    env = {**os.environ, "VBSIM_SCRIPTS_DIR": os.path.join(os.path.abspath(ROOT), "scripts")}
    return subprocess.run([VBSIM, "explore", definition_path, "-o", out, "--jobs", "2"], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True, env=env)


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


class ExploreRunTest(unittest.TestCase):
    def test_tiny_exploration(self):
        with tempfile.TemporaryDirectory() as d:
            definition = os.path.join(d, "def.json")
            with open(definition, "w") as f:
                json.dump(DEFINITION, f)
            out = os.path.join(d, "out")
            proc = explore(definition, out)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            self.assertIn("8 points, 0 already in the cache", proc.stderr)
            rows = read_rows(os.path.join(out, "points.csv"))
            self.assertEqual(len(rows), 2 * 2 * 2)  # workloads x methods x designs
            for column in ("workload", "method", "design", "avoidance.share", "area_mm2", "energy_pj_per_ray",
                           "cycles_per_ray", "mrays_per_s", "mrays_per_j", "errors_per_million", "ci95_low",
                           "ci95_high", "camera_errors_per_million", "pareto"):
                self.assertIn(column, rows[0])
            at = {(r["workload"], r["method"], r["avoidance.share"]): r for r in rows}
            for w in ("paths", "nested"):
                vb1, vb2 = at[(w, "validity-bit (vote)", "1")], at[(w, "validity-bit (vote)", "2")]
                p1, p2 = at[(w, "primid", "1")], at[(w, "primid", "2")]
                # Four cores: two groups of shared avoidance units instead of four, the validity bit's area only.
                self.assertLess(float(vb2["area_mm2"]), float(vb1["area_mm2"]))
                self.assertEqual(p1["area_mm2"], p2["area_mm2"])
                self.assertLess(float(p1["area_mm2"]), float(vb2["area_mm2"]))
                # The hits do not depend on the design, nor do the errors.
                self.assertEqual(vb1["errors_per_million"], vb2["errors_per_million"])
                self.assertGreater(int(vb1["secondary_scored"]), 0)
                self.assertLessEqual(float(vb1["ci95_low"]), float(vb1["errors_per_million"]))
                self.assertLessEqual(float(vb1["errors_per_million"]), float(vb1["ci95_high"]))
                self.assertEqual({r["pareto"] for r in (p1, p2)}, {"1"})  # equal rows: neither beats the other
            # The bundled paths trace through the oracle: 1,008 rays, 808 of them secondary and scored.
            self.assertEqual(at[("paths", "primid", "1")]["rays"], "1008")
            self.assertEqual(at[("paths", "primid", "1")]["secondary_scored"], "808")
            with open(os.path.join(out, "report.md")) as f:
                report = f.read()
            for text in ("Iso-area", "Iso-throughput", "Sensitivity", "validity-bit (vote)", "front-paths-45nm.png"):
                self.assertIn(text, report)
            self.assertTrue(os.path.getsize(os.path.join(out, "front-paths-45nm.png")) > 0)
            # A rerun resumes: every point comes from the cache, and the table is the same.
            again = explore(definition, out)
            self.assertEqual(again.returncode, 0, again.stderr)
            self.assertIn("8 points, 8 already in the cache, 0 to run", again.stderr)
            self.assertEqual(read_rows(os.path.join(out, "points.csv")), rows)

    def test_a_bad_definition_names_the_file_and_the_field(self):
        with tempfile.TemporaryDirectory() as d:
            definition = os.path.join(d, "def.json")
            with open(definition, "w") as f:
                json.dump({**DEFINITION, "designs": {"grid": {"avoidance.share": []}}}, f)
            proc = explore(definition, os.path.join(d, "out"))
            self.assertNotEqual(proc.returncode, 0)
            self.assertIn(definition, proc.stderr)
            self.assertIn("designs.grid.avoidance.share", proc.stderr)
            self.assertFalse(os.path.exists(os.path.join(d, "out", "points.csv")))

    def test_a_missing_trace_is_named(self):
        with tempfile.TemporaryDirectory() as d:
            definition = os.path.join(d, "def.json")
            with open(definition, "w") as f:
                json.dump({**DEFINITION, "workloads": [{"name": "gone", "trace": os.path.join(d, "none.jsonl")}]}, f)
            proc = explore(definition, os.path.join(d, "out"))
            self.assertNotEqual(proc.returncode, 0)
            self.assertIn("workload 'gone'", proc.stderr)


if __name__ == "__main__":
    VBSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
