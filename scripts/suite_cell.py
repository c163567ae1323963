#!/usr/bin/python3
"""One cell of the workload suite, a (scene, ray type): every method scored on
each preset (`vbsim score --mode cycle`) and the speed against Embree (`vbsim
bench`, functional and cycle-level) on the type's trace. scripts/suite.py runs
each cell as a point (scripts/point_jobs.py): here, or as a Slurm array task.

    suite_cell.py SETTINGS.json SCENE TYPE TRACE WORK OUT

SETTINGS.json holds vbsim, methods, testers, presets, bench_method,
bench_repeats and no_bench; the commands' tables and logs go to WORK, the
cell's figures to OUT (JSON).
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import suite_measure as measure  # noqa: E402

ROW_FIELDS = ("method", "tester", "kind", "rays", "errors", "self_hit", "false_hit", "missed", "rate", "lower", "upper")
# The kinds a captured trace holds (vbsim capture's linker names them), each scored apart for the `pathtracer` type.
CAPTURED_KINDS = ("primary", "shadow", "diffuse", "reflect", "refract")


def measure_cell(s, scene, rtype, trace, work):
    kind = "primary" if rtype == "primary" else "secondary"
    res = {"scene": scene, "type": rtype, "kind": kind, "runs": {}}
    methods = {}
    for preset in s["presets"]:
        info, table = measure.score(s["vbsim"], trace, preset, s["methods"], s["testers"],
                                    os.path.join(work, f"{rtype}.score-{preset}.json"),
                                    os.path.join(work, f"{rtype}.score-{preset}.log"))
        res["runs"][f"score-{preset}"] = info
        for row in measure.score_rows(table, kind):
            m = methods.setdefault((row["method"], row["tester"]), {k: row[k] for k in ROW_FIELDS})
            if "cycles_per_ray" in row:
                m[preset] = {k: row[k] for k in ("cycles_per_ray", "energy_per_ray_pj", "chip_mm2")}
    res["methods"] = list(methods.values())
    if rtype == "pathtracer":  # a whole renderer's rays: each kind's errors apart (the same on every preset)
        res["by_kind"] = [{k: row[k] for k in ROW_FIELDS} for kind_name in CAPTURED_KINDS
                          for row in measure.score_rows(table, kind_name)]
    if not s["no_bench"]:
        for mode in ("functional", "cycle"):
            res["runs"][f"bench-{mode}"] = measure.bench(
                s["vbsim"], trace, mode, s["bench_method"], s["bench_repeats"],
                os.path.join(work, f"{rtype}.bench-{mode}.json"), os.path.join(work, f"{rtype}.bench-{mode}.log"))
    return res


def main():
    if len(sys.argv) != 7:
        sys.exit(__doc__.strip().splitlines()[5].strip())
    settings_path, scene, rtype, trace, work, out = sys.argv[1:]
    with open(settings_path) as f:
        settings = json.load(f)
    try:
        res = measure_cell(settings, scene, rtype, trace, work)
    except measure.RunError as err:
        sys.exit(f"suite: {scene} {rtype}: {err}")
    with open(out, "w") as f:
        json.dump(res, f, indent=1)


if __name__ == "__main__":
    main()
