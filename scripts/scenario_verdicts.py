#!/usr/bin/env python3
"""Replays every trace of generated scenario folders with each method and prints a
Markdown table of summed verdicts (rays, self_hit, missed, false_hit) per folder
and method: the verdict table of docs/scenarios.md.

usage: scripts/scenario_verdicts.py [--vbsim BUILD/vbsim] [--methods a,b,...] DIR...
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

DEFAULT_METHODS = "none,tmin,primid,offset-normal,offset-direction,offset-adaptive,offset-errbound,validity-bit,offset-adaptive+primid"


def replay_dir(vbsim, folder, method):
    totals = {"rays": 0, "self_hit": 0, "missed": 0, "false_hit": 0}
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.json")
        for name in sorted(os.listdir(folder)):
            if not name.endswith(".jsonl"):
                continue
            subprocess.run([vbsim, "replay", os.path.join(folder, name), "-m", method, "-q", "--stats", stats],
                           check=True)
            with open(stats) as f:
                s = json.load(f)
            totals["rays"] += s["rays"]
            for k in ("self_hit", "missed", "false_hit"):
                totals[k] += s["verdicts"][k]
    return totals


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--vbsim", default=os.path.join(here, "..", "build", "vbsim"))
    ap.add_argument("--methods", default=DEFAULT_METHODS)
    ap.add_argument("dirs", nargs="+")
    a = ap.parse_args()
    methods = a.methods.split(",")
    print("| scenario | rays | " + " | ".join(f"`{m}`" for m in methods) + " |")
    print("|---|---|" + "---|" * len(methods))
    for folder in a.dirs:
        cells, rays = [], 0
        for m in methods:
            t = replay_dir(a.vbsim, folder, m)
            rays = t["rays"]
            cells.append(f"{t['self_hit']} / {t['missed']} / {t['false_hit']}")
        print(f"| {os.path.basename(os.path.normpath(folder))} | {rays} | " + " | ".join(cells) + " |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
