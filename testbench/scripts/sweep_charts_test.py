#!/usr/bin/python3
"""Breakdown points of stability sweeps on hand-made rows (scripts/sweep_charts.py)."""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from sweep_charts import breakdown_point, error_rate, plot_sweep  # noqa: E402


def row(x, self_hit=0, missed=0, rays=100, unscored=0):
    return {"x": x, "method": "m", "rays": rays, "unscored": unscored, "correct": rays - self_hit - missed,
            "self_hit": self_hit, "false_hit": 0, "missed": missed}


class BreakdownTest(unittest.TestCase):
    def test_error_rate_counts_scored_rays_only(self):
        self.assertAlmostEqual(error_rate(row(1, self_hit=3, missed=1, rays=100, unscored=20)), 4 / 80)

    def test_hard_low_names_the_largest_failing_value(self):
        rows = [row(1, self_hit=5), row(2, self_hit=1), row(4), row(8)]
        self.assertEqual(breakdown_point({"hard": "low"}, rows), "2 and below")

    def test_hard_high_names_the_smallest_failing_value(self):
        rows = [row(1), row(2), row(4, missed=2), row(8, missed=9)]
        self.assertEqual(breakdown_point({"hard": "high", "unit": "deg"}, rows), "4 deg and above")

    def test_non_monotone_errors_are_said(self):
        rows = [row(1, self_hit=1), row(2), row(4, self_hit=1), row(8)]
        self.assertEqual(breakdown_point({"hard": "low"}, rows), "4 (errors not monotone)")

    def test_both_ends_give_the_error_free_window(self):
        rows = [row(1, self_hit=5), row(2), row(4), row(8, missed=1)]
        self.assertEqual(breakdown_point({"hard": "both"}, rows), "error-free from 2 to 4")
        self.assertEqual(breakdown_point({"hard": "both"}, [row(1, missed=1)]), "fails at every point")

    def test_chart_is_written(self):
        sweep = {"title": "t", "xlabel": "x", "xlog": True, "methods": [{"label": "m"}]}
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "c.png")
            plot_sweep(sweep, [row(1, self_hit=1), row(10)], path)
            with open(path, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main()
