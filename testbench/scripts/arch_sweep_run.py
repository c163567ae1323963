#!/usr/bin/python3
"""Runs scripts/arch_sweep.py on a tiny definition (a ~300-ray paths trace, one
core and two cores with ideal memory, two methods on one small scenario family)
and checks what it writes: the chart, the page, the JSON rows, method_cycles.json,
and that two cores give more rays per cycle than one.

    /usr/bin/python3 arch_sweep_run.py PATH_TO_VBSIM
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
VBSIM = None

DEFINITION = {
    "trace": {"scenario": "paths", "rays": 64, "seed": 1},
    "method": "validity-bit",
    "sweeps": [{"name": "cores", "title": "cores", "chart": "scaling", "x": "cores", "xlabel": "cores",
                "preset": "small", "values": [1, 2],
                "series": [{"label": "ideal", "hw": {"memory": {"ideal": True}}, "bound": True}]}],
    "families": {"rays": 10, "seed": 1, "max_traces": 1, "scenarios": ["coplanar"], "bundled": [],
                 "methods": ["none", "validity-bit:vb-policy=vote"]},
}


class ArchSweepRunTest(unittest.TestCase):
    def test_tiny_sweep_writes_charts_and_json_and_scales(self):
        with tempfile.TemporaryDirectory() as d:
            definition = os.path.join(d, "def.json")
            with open(definition, "w") as f:
                json.dump(DEFINITION, f)
            out, results = os.path.join(d, "out"), os.path.join(d, "results")
            cmd = [sys.executable, os.path.join(ROOT, "scripts", "arch_sweep.py"), "--vbsim", VBSIM,
                   "--definition", definition, "--work", os.path.join(d, "work"), "--out", out,
                   "--results", results, "--jobs", "2"]
            proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            self.assertEqual(proc.returncode, 0, proc.stderr)

            with open(os.path.join(out, "arch-cores.png"), "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
            with open(os.path.join(out, "architecture.md")) as f:
                page = f.read()
            self.assertIn("![cores](arch-cores.png)", page)
            self.assertIn("--definition", page)

            with open(os.path.join(results, "arch_sweep.json")) as f:
                rows = {r["x"]: r for r in json.load(f)["rows"]}
            self.assertEqual(sorted(rows), [1, 2])
            self.assertGreaterEqual(rows[1]["rays"], 250)
            self.assertEqual((rows[1]["cores"], rows[2]["cores"]), (1, 2))
            self.assertGreater(rows[2]["rays_per_cycle"], 1.2 * rows[1]["rays_per_cycle"])
            for r in rows.values():  # never above the analytic bound
                self.assertLessEqual(r["rays_per_cycle"], r["bound"] * 1.0001)

            with open(os.path.join(results, "method_cycles.json")) as f:
                cycles = json.load(f)
            self.assertEqual(cycles["preset"], "small")
            keys = [(r["family"], r["method"]) for r in cycles["rows"]]
            self.assertEqual(keys, [("coplanar", "none"), ("coplanar", "validity-bit:vb-policy=vote")])
            for r in cycles["rows"]:
                self.assertAlmostEqual(r["cycles_per_ray"], r["cycles"] / r["rays"])
                # one slot has no overlap: each ray costs at least its own latency
                self.assertGreaterEqual(r["one_core_one_slot"]["cycles_per_ray"],
                                        r["one_core_one_slot"]["mean_latency"])

            # A second run finds every point in the cache and writes the same rows.
            again = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            self.assertEqual(again.returncode, 0, again.stderr)
            with open(os.path.join(results, "arch_sweep.json")) as f:
                self.assertEqual({r["x"]: r for r in json.load(f)["rows"]}, rows)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: arch_sweep_run.py PATH_TO_VBSIM")
    VBSIM = sys.argv.pop(1)
    unittest.main()
