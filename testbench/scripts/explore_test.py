#!/usr/bin/python3
"""Pieces of the design-space exploration (scripts/explore_definition.py,
explore_points.py, explore_analysis.py) on hand-made inputs."""
import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from explore_analysis import iso_area, iso_throughput, sensitivity  # noqa: E402
from explore_definition import DefinitionError, expand_designs, load_definition  # noqa: E402
from explore_points import mark_pareto, wilson  # noqa: E402


def row(design, area, energy, cycles, method="m", workload="w", mrays=None, **knobs):
    return {"workload": workload, "method": method, "tech": "45nm", "design": design, "area_mm2": area,
            "energy_pj_per_ray": energy, "cycles_per_ray": cycles,
            "mrays_per_s": mrays if mrays is not None else 1000.0 / cycles, **knobs}


class WilsonTest(unittest.TestCase):
    def test_no_errors_in_808_rays_by_hand(self):
        # p = 0: the interval is [0, z^2 / (n + z^2)] = [0, 3.84146 / 811.84146].
        low, high = wilson(0, 808)
        self.assertEqual(low, 0.0)
        self.assertAlmostEqual(high, 3.841459 / 811.841459 * 1e6, delta=0.01)

    def test_two_errors_in_808_rays_by_hand(self):
        # centre (p + z^2/2n) / (1 + z^2/n) = 0.0048293, half width 0.0041504 (computed by hand).
        low, high = wilson(2, 808)
        self.assertAlmostEqual(low, 679.0, delta=1.0)
        self.assertAlmostEqual(high, 8980.0, delta=1.0)

    def test_no_rays_no_interval(self):
        low, high = wilson(0, 0)
        self.assertNotEqual(low, low)  # NaN
        self.assertNotEqual(high, high)


class ParetoTest(unittest.TestCase):
    def test_a_row_beaten_on_every_axis_leaves_the_front(self):
        rows = [row("a", 5.0, 100.0, 10.0), row("b", 6.0, 110.0, 11.0), row("c", 7.0, 90.0, 12.0),
                row("d", 5.0, 100.0, 10.0)]
        mark_pareto(rows)
        # b is beaten by a on area, energy and cycles; c is the least energy; a and d tie (neither beats the other).
        self.assertEqual([r["pareto"] for r in rows], [1, 0, 1, 1])

    def test_fronts_are_per_workload_and_method(self):
        rows = [row("a", 5.0, 100.0, 10.0, method="x"), row("b", 6.0, 110.0, 11.0, method="y"),
                row("c", 6.0, 110.0, 11.0, workload="v", method="x")]
        mark_pareto(rows)
        self.assertEqual([r["pareto"] for r in rows], [1, 1, 1])


class DesignsTest(unittest.TestCase):
    def test_grid_list_and_random_without_repeats(self):
        designs = expand_designs("d.json", {"grid": {"cores": [1, 2], "avoidance.share": [1, 4]},
                                            "list": [{"cores": 1, "avoidance.share": 1}, {"cores": 8}]})
        self.assertEqual(len(designs), 5)  # 2 x 2 grid, the list's first already there, {cores: 8} new
        self.assertEqual(designs[-1], {"cores": 8})
        drawn = expand_designs("d.json", {"random": {"samples": 10, "seed": 7, "space": {"a": [1, 2], "b": [3]}}})
        self.assertEqual(sorted(d["a"] for d in drawn), [1, 2])  # the space holds two designs
        again = expand_designs("d.json", {"random": {"samples": 2, "seed": 7, "space": {"a": [1, 2, 3, 4, 5]}}})
        self.assertEqual(again, expand_designs("d.json", {"random": {"samples": 2, "seed": 7,
                                                                     "space": {"a": [1, 2, 3, 4, 5]}}}))

    def test_no_designs_is_the_preset_alone(self):
        self.assertEqual(expand_designs("d.json", None), [{}])


class DefinitionErrorsTest(unittest.TestCase):
    def check_error(self, definition, field):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "def.json")
            with open(path, "w") as f:
                f.write(definition if isinstance(definition, str) else json.dumps(definition))
            with self.assertRaises(DefinitionError) as e:
                load_definition(path)
            self.assertIn(path, str(e.exception))
            self.assertIn(field, str(e.exception))

    def test_each_error_names_the_file_and_the_field(self):
        ok = {"workloads": [{"name": "w", "trace": "t.jsonl"}], "methods": ["primid"]}
        self.check_error({**ok, "desings": {}}, "'desings'")
        self.check_error({**ok, "methods": []}, "'methods'")
        self.check_error({**ok, "methods": ["primid", "primid"]}, "'methods'")
        self.check_error({**ok, "workloads": [{"name": "w", "trace": "t", "render": {"scene": "s"}}]},
                         "'workloads[0]'")
        self.check_error({**ok, "workloads": [{"name": "w", "render": {"scene": "s", "sppp": 2}}]},
                         "'workloads[0].render.sppp'")
        self.check_error({**ok, "designs": {"grid": {"cores": []}}}, "'designs.grid.cores'")
        self.check_error({**ok, "designs": {"grid": {"preset": ["large"]}}}, "'designs.grid'")
        self.check_error({**ok, "area_budgets_mm2": [-1]}, "'area_budgets_mm2'")
        self.check_error('{"workloads": [\n  1,\n}', "line 3")


class AnalysisTest(unittest.TestCase):
    def test_iso_area_takes_the_fastest_design_that_fits(self):
        rows = [row("small", 5.0, 1.0, 20.0, method="x"), row("big", 9.0, 1.0, 10.0, method="x"),
                row("only", 8.0, 1.0, 15.0, method="y")]
        (at6,) = iso_area(rows, [6.0])
        self.assertEqual(at6["best"]["x"]["design"], "small")
        self.assertIsNone(at6["best"]["y"])  # y has no design within 6 mm2
        (at10,) = iso_area(rows, [10.0])
        self.assertEqual(at10["best"]["x"]["design"], "big")

    def test_iso_throughput_takes_the_smallest_and_the_most_frugal_design_reaching_the_target(self):
        rows = [row("slow", 4.0, 1.0, 20.0), row("fast-big", 9.0, 1.0, 10.0), row("fast-small", 8.0, 3.0, 12.5)]
        (entry,) = iso_throughput(rows, [80.0])  # 1000 / cycles: 50, 100, 80 Mrays/s
        self.assertEqual(entry["smallest"]["m"]["design"], "fast-small")
        self.assertEqual(entry["frugal"]["m"]["design"], "fast-big")

    def test_sensitivity_is_each_knobs_main_effect(self):
        # cycles = 10 at a=1 and 12 at a=2 whatever b is: a moves it (12 - 10) / 11 = 18.2%, b not at all.
        rows = [row(f"{a}{b}", 5.0, 1.0, 10.0 + 2 * (a - 1), a=a, b=b) for a in (1, 2) for b in (1, 2)]
        effects = sensitivity(rows, ["a", "b"], "cycles_per_ray")["m"]
        self.assertAlmostEqual(effects["a"], 2 / 11)
        self.assertAlmostEqual(effects["b"], 0.0)


if __name__ == "__main__":
    unittest.main()
