#!/usr/bin/python3
"""scripts/rtcore_crossval.py without rtcore-systemc: it skips with a message and writes
nothing; its reading of rtcore's log and its measured cycle, on a log made by hand; its
page over both of vbsim's trees, from figures made by hand."""
import os
import subprocess
import sys
import tempfile
import unittest
from unittest import mock

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import rtcore_crossval  # noqa: E402

# Three rays in two slots: ray 0 in slot 0 (sent 1, done 50), ray 1 in slot 1 (sent 3,
# done 40), ray 2 in slot 1 again (sent 41, done 90); then the counts rtcore prints.
LOG = """m_shader @ 1,READ: ray sent, id=0 (count=1)
m_shader @ 3,READ: ray sent, id=1 (count=2)
m_shader @ 40,READ: result received, id=1
m_shader @ 41,READ: ray sent, id=1 (count=3)
m_shader @ 50,READ: result received, id=0
m_shader @ 90,READ: result received, id=1
m_rtcore.m_ist_l1c:
miss = 7
hit = 3
m_rtcore.m_bbox_l1c_lp:
miss = 2
hit = 20
ist processed 12 triangles
hp processed 4 nodes
lp processed 9 nodes
"""


class CrossvalTest(unittest.TestCase):
    def test_skips_without_the_source(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "page.md")
            env = {k: v for k, v in os.environ.items() if k != "VBSIM_RTCORE_SRC"}
            r = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts", "rtcore_crossval.py"), "--out", out],
                               capture_output=True, text=True, env=env)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("skipped", r.stdout)
            self.assertFalse(os.path.exists(out))

    def test_reads_rtcores_log(self):
        done = mock.Mock(stdout=LOG, returncode=0)
        with mock.patch.object(rtcore_crossval, "run", return_value=done), \
                mock.patch.object(rtcore_crossval, "TAIL_RAYS", 1):
            got = rtcore_crossval.run_rtcore("/x/tb_top", "m.ply", "r.bin", [512] * 3 + [0.5, 0.47, 4, 4, 1], 3)
        self.assertEqual(got["latency"], [49, 37, 49])
        self.assertEqual(got["cycles"], 50)  # all but the last 1 of 3 rays finished by cycle 50
        self.assertEqual(got["end"], 90)
        self.assertEqual(got["counts"], {"m_rtcore.m_ist_l1c.miss": 7, "m_rtcore.m_ist_l1c.hit": 3,
                                         "m_rtcore.m_bbox_l1c_lp.miss": 2, "m_rtcore.m_bbox_l1c_lp.hit": 20,
                                         "ist": 12, "hp": 4, "lp": 9})

    def test_measured_cycle_needs_enough_finished_rays(self):
        with mock.patch.object(rtcore_crossval, "TAIL_RAYS", 2):
            self.assertEqual(rtcore_crossval.measured_cycle([30, 10, 20, 40], 5), 30)  # the 3rd of 5
            with self.assertRaises(SystemExit):
                rtcore_crossval.measured_cycle([10], 5)

    def test_page_has_both_trees(self):
        args = [512] * 3 + [0.5, 0.47, 4, 4, 1]
        n = 4
        rt = {"cycles": 300, "end": 400, "latency": [100, 110, None, 120],
              "counts": {"lp": 16, "hp": 4, "ist": 8, "m_rtcore.m_ist_l1c.miss": 6}}

        def vbsim(cycles, box_ops, triangle_ops):
            return {"cycles": cycles, "latency": [90, 100, 95, 130],
                    "hw": {"utilisation": {"box": 0.5, "triangle": 0.95},
                           "units": {"box": {"ops": box_ops}, "triangle": {"ops": triangle_ops}},
                           "memory": {"port": {"l1": {"misses": 5}, "dram": {"reads": 5}}}}}

        with mock.patch.object(rtcore_crossval, "TAIL_RAYS", 1):
            rows = [{"embree": rtcore_crossval.row("a regime", "bound", args, rt, vbsim(294, 16, 8), n),
                     "sweep": rtcore_crossval.row("a regime", "bound", args, rt, vbsim(288, 15, 7), n)}]
            text = rtcore_crossval.page(rows, n, os.path.join(ROOT, "traces", "x.obj"), "rays.bin")
        self.assertAlmostEqual(rows[0]["embree"]["difference"], -0.02)
        self.assertAlmostEqual(rows[0]["sweep"]["difference"], -0.04)
        self.assertIn("vbsim over its default tree (Embree's", text)
        self.assertIn("`--bvh-builder sweep-sah --bvh-leaf-size 16`", text)
        self.assertEqual(text.count("Within 5%: 1 of 1 regimes."), 2)
        self.assertIn("| a regime | -2.0% | -4.0% | +2.0 points |", text)
        self.assertIn("- **a regime** (-2.0%; -4.0% over the sweep-SAH tree)", text)

    def test_memory_bound_residual_by_hand(self):
        # 4 rays, no unit near busy; rtcore misses 4 low-precision nodes, 2 other
        # nodes and 2 triangles: (4 x 40 + 2 x 52 + 2 x 36) x 5 / 4 = 420 to
        # (4 x 40 + 2 x 64 + 2 x 36) x 5 / 4 = 450 DRAM cycles a ray. vbsim misses
        # 5, 2 and 2 objects (9: 2.25 a ray, +12.5%) of 400 bytes:
        # (400 x 5 + 9) / 4 = 502.25 cycles a ray, +11.6% to +19.6%.
        args = [64] * 3 + [0.5, 0.47, 32, 32, 32]
        rt = {"cycles": 300, "end": 400, "latency": [100, 110, 120, 130],
              "counts": {"lp": 16, "hp": 4, "ist": 8, "m_rtcore.m_bbox_l1c_lp.miss": 4,
                         "m_rtcore.m_bbox_l1c_hp.miss": 2, "m_rtcore.m_ist_l1c.miss": 2}}
        objects = {"node_low": {"misses": 5}, "node": {"misses": 2}, "triangle": {"misses": 2}}
        vb = {"cycles": 330, "latency": [100, 120, 130, 140],
              "hw": {"utilisation": {"box": 0.05, "triangle": 0.1},
                     "units": {"box": {"ops": 20}, "triangle": {"ops": 8}},
                     "memory": {"port": {"l1": {"misses": 9}, "objects": objects,
                                         "dram": {"reads": 9, "bytes": 400}}}}}
        with mock.patch.object(rtcore_crossval, "TAIL_RAYS", 1):
            r = rtcore_crossval.row("caches", "cache-bound", args, rt, vb, 4)
        text = rtcore_crossval.explain(r, "a tree")
        self.assertIn("misses a ray by cache, rtcore 1.00, 0.50, 0.50, vbsim 1.25, 0.50, 0.50 (+12.5% in all)", text)
        self.assertIn("their DRAM cycles a ray, vbsim 502, rtcore 420 to 450 (+11.6% to +19.6%)", text)


if __name__ == "__main__":
    unittest.main()
