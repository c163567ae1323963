#!/usr/bin/python3
"""scripts/scaling.py end to end on its smallest settings: two subdivided scenes, two ray
counts; the CSV has every (series, mode) row with the scenes' triangle counts and the ray
counts asked for, and the page lists finite fitted exponents for each quantity (no figure
is held to a time: speeds vary with the machine)."""
import csv
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    vbsim = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        page = os.path.join(tmp, "s.md")
        subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts", "scaling.py"), "--vbsim", vbsim,
                        "--rounds", "2", "--rays", "3000", "--ray-counts", "2000,8000", "--ray-scene-rounds", "1",
                        "--out", tmp, "--page", page], check=True, capture_output=True)
        rows = list(csv.DictReader(open(os.path.join(tmp, "s.csv"))))
        text = open(page).read()
        assert os.path.getsize(os.path.join(tmp, "s.png")) > 0
    assert len(rows) == 8, rows
    tri = [r for r in rows if r["series"] == "triangles"]
    assert sorted({int(r["triangles"]) for r in tri}) == [14928, 59712], tri  # Wuson split into four, twice
    assert {int(r["rays"]) for r in tri} == {3000}
    assert sorted(int(r["rays"]) for r in rows if r["series"] == "rays") == [2000, 2000, 8000, 8000]
    for r in rows:
        assert float(r["vbsim_rays_per_s"]) > 0 and float(r["embree_rays_per_s"]) > 0, r
        assert int(r["peak_rss_bytes"]) > 10 * 2**20, r  # the program and its libraries alone pass 10 MiB
        assert float(r["bvh_build_s"]) >= 0 and 0 < float(r["ratio"]), r
    for quantity in ("build", "rss", "time per ray", "run time against rays"):
        for mode in ("functional", "cycle"):
            line = next(l for l in text.splitlines() if l.startswith(f"| {mode} | {quantity} |"))
            assert all(math.isfinite(float(x)) for x in line.strip("|").split("|")[2:]), line
    print("scaling_run: ok")


if __name__ == "__main__":
    main()
