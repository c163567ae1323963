#!/usr/bin/python3
"""scripts/rtcore_config.py: rtcore-systemc's tb_top arguments, in its order and with
its defaults, become a configuration vbsim accepts, with the sizes computed by hand.

    /usr/bin/python3 rtcore_config_run.py PATH_TO_VBSIM
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SCRIPT = os.path.join(ROOT, "scripts", "rtcore_config.py")
VBSIM = None


def run(*args):
    return subprocess.run(["/usr/bin/python3", SCRIPT, *map(str, args)], capture_output=True, text=True)


class RtcoreConfigTest(unittest.TestCase):
    def test_defaults_are_rtcores(self):
        r = run()
        self.assertEqual(r.returncode, 0, r.stderr)
        out = json.loads(r.stdout)
        hw = out["hw"]
        self.assertEqual(hw["preset"], "rtcore")
        # rtcore's three object caches: 512 entries each of its objects' sizes.
        self.assertEqual(hw["memory"]["objects"], {"node_low": {"entries": 512, "bytes": 40},
                                                   "node": {"entries": 512, "bytes": 64},
                                                   "triangle": {"entries": 512, "bytes": 36}})
        self.assertEqual(hw["box"], {"count": 4, "latency": 20, "issue_interval": 20})  # NUM_HP
        self.assertEqual(hw["box_low"], {"count": 4, "latency": 20, "issue_interval": 20})  # NUM_LP
        self.assertEqual(hw["triangle"], {"count": 1, "latency": 32, "issue_interval": 32})
        self.assertEqual(out["bvh"], {"low_precision": {"mantissa_bits": 7, "t_trav_high": 0.5, "t_trav_low": 0.47,
                                                        "narrow_arithmetic": True}})
        self.assertIn("not modelled", r.stderr)  # what the mapping cannot express is named

    def test_arguments_in_tb_tops_order(self):
        r = run(16, 32, 8, 0.5, 0.47, 2, 2, 3)
        self.assertEqual(r.returncode, 0, r.stderr)
        out = json.loads(r.stdout)
        hw = out["hw"]
        # LP_L1C_ENTRIES, HP_L1C_ENTRIES, IST_L1C_ENTRIES: the three caches' entries.
        self.assertEqual([hw["memory"]["objects"][k]["entries"] for k in ("node_low", "node", "triangle")],
                         [16, 32, 8])
        self.assertEqual(hw["box"]["count"], 2)
        self.assertEqual(hw["box_low"]["count"], 2)
        self.assertEqual(hw["triangle"]["count"], 3)
        r = run(512, 512, 512, 0.6, 0.3, 4, 8)
        out = json.loads(r.stdout)
        self.assertEqual(out["hw"]["box"]["count"], 8)  # NUM_HP
        self.assertEqual(out["hw"]["box_low"]["count"], 4)  # NUM_LP
        self.assertEqual(out["bvh"]["low_precision"]["t_trav_high"], 0.6)
        self.assertEqual(out["bvh"]["low_precision"]["t_trav_low"], 0.3)

    def test_bad_arguments(self):
        for args, field in [(["x"], "LP_L1C_ENTRIES"), ([512, 512, 512, "high"], "T_TRAV_HIGH"),
                            ([512, 512, 512, 0.5, 0.47, 0], "NUM_LP"), ([1] * 9, "at most 8")]:
            r = run(*args)
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(field, r.stderr)
            self.assertEqual(r.stdout, "")

    def test_vbsim_takes_it(self):
        with tempfile.TemporaryDirectory() as tmp:
            cfg = os.path.join(tmp, "rtcore.json")
            with open(cfg, "w") as f:
                f.write(run(16, 16, 16, 0.5, 0.47, 1, 1, 2).stdout)
            out = os.path.join(tmp, "hw.json")
            r = subprocess.run([VBSIM, "hw", "--config", cfg, "--json", out], capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out) as f:
                hw = json.load(f)["config"]
            # The object caches, the rest of their parameters from the preset.
            self.assertEqual(hw["memory"]["objects"]["node_low"], {"entries": 16, "bytes": 40})
            self.assertEqual(hw["memory"]["objects"]["triangle"], {"entries": 16, "bytes": 36})
            self.assertEqual(hw["memory"]["objects"]["port_cycles"], 2)
            self.assertEqual(hw["memory"]["objects"]["responses_per_cycle"], 1)
            self.assertEqual(hw["memory"]["dram_latency_per_byte"], 5)
            self.assertEqual(hw["triangle"]["count"], 2)
            self.assertEqual(hw["box_low"]["count"], 1)
            self.assertEqual(hw["cores"], 1)
            # A replay takes it too, with its node marking.
            stats = os.path.join(tmp, "stats.json")
            trace = os.path.join(ROOT, "traces", "bunny", "paths.jsonl")
            r = subprocess.run([VBSIM, "replay", trace, "--mode", "cycle", "--config", cfg, "--stats", stats, "-q"],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(stats) as f:
                s = json.load(f)
            self.assertEqual(s["config"]["bvh"]["low_precision"]["t_trav_low"], 0.47)
            self.assertGreater(s["hw"]["units"]["box_low"]["ops"], 0)


if __name__ == "__main__":
    VBSIM = sys.argv.pop(1)
    unittest.main()
