#!/usr/bin/python3
"""Pieces of the architecture sweep (scripts/arch_points.py, arch_families.py,
arch_report.py) on hand-made inputs."""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from arch_families import sample  # noqa: E402
from arch_points import bound_terms, merge, method_args, point_key, set_path  # noqa: E402
from arch_report import limit_text  # noqa: E402


def stats(rays, source_busy, box_ops_per_ray, tri_ops_per_ray, cores=4, box_count=1, tri_interval=2):
    unit = {"count": 1, "issue_interval": 1}
    return {"hw": {"rays": rays, "source": {"busy_cycles": source_busy},
                   "units": {"box": {"ops_per_ray": box_ops_per_ray}, "triangle": {"ops_per_ray": tri_ops_per_ray},
                             "avoidance": {"ops_per_ray": 0.0}}},
            "config": {"hw": {"cores": cores, "box": {**unit, "count": box_count},
                              "triangle": {**unit, "issue_interval": tri_interval}, "avoidance": unit}}}


class MethodArgsTest(unittest.TestCase):
    def test_spec_keys_become_replay_options(self):
        self.assertEqual(method_args("validity-bit:vb-eps-mode=fixed:vb-eps=1e-4:vb-policy=vote"),
                         ["--method", "validity-bit", "--vb-eps-mode", "fixed", "--vb-eps", "1e-4",
                          "--vb-policy", "vote"])

    def test_composition_stays_one_method_and_tests_use_commas(self):
        self.assertEqual(method_args("offset-adaptive+primid"), ["--method", "offset-adaptive+primid"])
        self.assertEqual(method_args("validity-bit:vb-tests=normal+component"),
                         ["--method", "validity-bit", "--vb-tests", "normal,component"])

    def test_an_option_without_value_stops_the_run(self):
        with self.assertRaises(SystemExit):
            method_args("tmin:tmin-eps")


class PointKeyTest(unittest.TestCase):
    def test_a_rebuilt_model_does_not_reuse_cached_points(self):
        with tempfile.TemporaryDirectory() as d:
            paths = {}
            for name, text in (("old", b"model A"), ("new", b"model B"), ("same", b"model A"), ("trace", b"{}")):
                paths[name] = os.path.join(d, name)
                with open(paths[name], "wb") as f:
                    f.write(text)
            key = lambda binary: point_key(paths[binary], paths["trace"], {"cores": 1}, "none")  # noqa: E731
            self.assertNotEqual(key("old"), key("new"))
            self.assertEqual(key("old"), key("same"))  # the same bytes: the cache holds


class BoundTest(unittest.TestCase):
    def test_each_term_by_hand(self):
        # 4 cores x 2 box pipelines / 16 box ops per ray = 0.5; 4 cores x 1 / (2 x 3 ops) = 0.667;
        # the source: 1000 rays in 1250 busy cycles = 0.8 rays per cycle.
        t = bound_terms(stats(1000, 1250, 16.0, 3.0, cores=4, box_count=2))
        self.assertAlmostEqual(t["box"], 0.5)
        self.assertAlmostEqual(t["triangle"], 4 / 6)
        self.assertAlmostEqual(t["source"], 0.8)
        self.assertNotIn("avoidance", t)  # no suspects: the unit sets no bound

    def test_emission_lanes_multiply_the_source_bound(self):
        # 4 lanes share 1250 busy lane-cycles for 1000 rays: 4 x 0.8 rays per cycle.
        s = stats(1000, 1250, 16.0, 3.0)
        s["config"]["hw"]["source"] = {"rays_per_cycle": 4}
        self.assertAlmostEqual(bound_terms(s)["source"], 3.2)

    def test_limit_names_the_bound_unit_when_reached(self):
        r = {"bound_terms": {"source": 1.0, "box": 0.25}, "rays_per_cycle": 0.24, "cores": 4,
             "slots_per_core": 32, "rays": 10000}
        self.assertTrue(limit_text(r).startswith("box-pipeline bound (96%"))

    def test_limit_names_the_largest_stall_below_the_bound(self):
        r = {"bound_terms": {"source": 1.0, "box": 0.25}, "rays_per_cycle": 0.1, "cores": 4, "slots_per_core": 32,
             "rays": 10000, "ideal_memory": True, "mean_latency": 500, "utilisation": {"slots": 0.99},
             "stall_shares": {"memory_wait": 0.5, "box_pipeline_full": 0.2, "triangle_pipeline_full": 0,
                              "avoidance_pipeline_full": 0, "stack_refill_wait": 0}}
        self.assertEqual(limit_text(r), "40% of the box-pipeline bound; memory wait takes 50% of slot-cycles")


class HelpersTest(unittest.TestCase):
    def test_sample_is_even_and_keeps_both_ends(self):
        self.assertEqual(sample(list(range(100)), 4), [0, 33, 66, 99])
        self.assertEqual(sample([1, 2], 8), [1, 2])

    def test_set_path_and_merge_leave_their_inputs_alone(self):
        base = {"memory": {"ideal": False, "l1": {"size_bytes": 16384}}}
        out = set_path(base, "memory.l1.size_bytes", 1024)
        self.assertEqual(out["memory"]["l1"]["size_bytes"], 1024)
        self.assertEqual(base["memory"]["l1"]["size_bytes"], 16384)
        self.assertEqual(merge(base, {"memory": {"ideal": True}}),
                         {"memory": {"ideal": True, "l1": {"size_bytes": 16384}}})


if __name__ == "__main__":
    unittest.main()
