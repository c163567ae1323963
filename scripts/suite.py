#!/usr/bin/python3
"""The workload suite: every scene of a scene list (traces/suite/scenes.json)
times every ray type (primary, shadow, ambient occlusion, diffuse bounces 1 to
3, mirror, glass), each scored by every method with 95% intervals, timed on the
cycle-level model's presets and against Embree (docs/suite.md).

    /usr/bin/python3 scripts/suite.py --small              # three small scenes, few rays (seconds)
    /usr/bin/python3 scripts/suite.py --tier medium --size 128x128 --page docs/results/suite.md
    /usr/bin/python3 scripts/suite.py --prepare-only --tier huge   # make the 13 M-triangle scene

Scenes are prepared into OUT/scenes (default build/suite; never committed), each
(scene, ray type)'s traces and tables go to OUT/runs, the results (suite.json,
suite.csv, suite-speed.csv) to OUT/results, and the page (--page) is written
from them.
"""
import argparse
import hashlib
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import point_jobs  # noqa: E402
import suite_measure as measure  # noqa: E402
import suite_rays as rays  # noqa: E402
import suite_report as report  # noqa: E402
import suite_scenes as scenes  # noqa: E402
from point_jobs import file_digest  # noqa: E402

SMALL = {"tier": "small", "size": "32x32", "spp": 1, "glass_bounces": 3, "max_rays": 1000, "bench_repeats": 1}
DEFAULT = {"tier": "medium", "size": "128x128", "spp": 1, "glass_bounces": 3, "max_rays": 0, "bench_repeats": 2}


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--list", default=scenes.DEFAULT_LIST, help="the scene list [traces/suite/scenes.json]")
    ap.add_argument("--small", action="store_true", help="the small end: tier small, a 32x32 frame, at most 1000 rays a type")
    ap.add_argument("--tier", help="scenes of this tier of the list (small, medium, full, huge) [medium; small with --small]")
    ap.add_argument("--scenes", help="comma list of scene names (instead of a tier's)")
    ap.add_argument("--types", default=",".join(rays.TYPES), help="comma list of ray types [all]")
    ap.add_argument("--size", help="frame WxH of the renders [128x128; 32x32 with --small]")
    ap.add_argument("--spp", type=int, help="paths a pixel of the path tracer [1]")
    ap.add_argument("--glass-bounces", type=int,
                    help="refractions and reflections a path of the glass render takes at most [3]")
    ap.add_argument("--max-rays", type=int, help="at most this many rays a type, taken evenly (0: all) [0; 1000]")
    ap.add_argument("--ao-radius", type=float, default=0.1, help="ambient-occlusion ray length, times the scene's bounding-box diagonal [0.1]")
    ap.add_argument("--methods", default="", help="vbsim score --methods [score's default: every method]")
    ap.add_argument("--testers", default="three-half-plane", help="vbsim score --testers [three-half-plane]")
    ap.add_argument("--presets", default="small,large", help="cycle-level presets [small,large]")
    ap.add_argument("--bench-method", default="validity-bit", help="method of the speed runs [validity-bit]")
    ap.add_argument("--bench-repeats", type=int, help="vbsim bench --repeats [2; 1 with --small]")
    ap.add_argument("--no-bench", action="store_true", help="skip the speed runs against Embree")
    ap.add_argument("--prepare-only", action="store_true", help="prepare the scenes and stop")
    ap.add_argument("--out", default=os.path.join(scenes.ROOT, "build", "suite"), help="work directory [build/suite]")
    ap.add_argument("--page", help="write the markdown page here [OUT/results/suite.md]")
    ap.add_argument("--vbsim", default=os.path.join(scenes.ROOT, "build", "vbsim"))
    point_jobs.add_backend_arguments(ap)
    ap.set_defaults(jobs=1)  # one cell at a time here: the speeds are measured alone
    a = ap.parse_args(argv)
    point_jobs.check_backend_arguments(ap, a)
    preset = SMALL if a.small else DEFAULT
    for key, value in preset.items():
        if getattr(a, key, None) is None:
            setattr(a, key, value)
    try:
        a.width, a.height = (int(x) for x in a.size.lower().split("x"))
    except ValueError:
        ap.error(f"--size {a.size}: expected WxH")
    a.types = [t for t in a.types.split(",") if t]
    for t in a.types:
        if t not in rays.TYPES:
            ap.error(f"--types: '{t}' is not one of {','.join(rays.TYPES)}")
    a.presets = [p for p in a.presets.split(",") if p]
    return a


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def run_key(a, meta):
    """What a scene's runs depend on: the scene, the ray options, the vbsim binary."""
    parts = {"scene": meta["key"], "size": a.size, "spp": a.spp, "glass": a.glass_bounces, "max": a.max_rays,
             "ao": a.ao_radius, "vbsim": file_digest(a.vbsim)}
    return hashlib.sha256(json.dumps(parts, sort_keys=True).encode()).hexdigest()[:16]


def make_type_traces(a, entry, meta, work):
    """Runs the sources the wanted types need, splits them, fills in the exact
    answers; returns {type: {"trace", "rays", "source_rays", "source"}} and the
    source runs' figures."""
    commands = rays.source_commands(a.vbsim, meta["ply"], scenes.point_light(meta), a, work,
                                    scenes.pathtracer_camera(meta))
    needed = sorted({rays.SOURCE_OF[t] for t in a.types})
    out, sources = {}, {}
    for src in needed:
        done = os.path.join(work, src + ".done.json")
        wanted = [t for t in a.types if rays.SOURCE_OF[t] == src]
        info = None
        if os.path.exists(done):
            with open(done) as f:
                info = json.load(f)
            if not set(wanted) <= set(info["types"]):
                info = None  # made for fewer types: make again
        if info is None:
            log(f"suite: {entry['name']}: {src} source")
            info = measure.run(commands[src], os.path.join(work, src + ".log"))
            split = rays.split(src, rays.source_trace(src, work), wanted, work, a.max_rays)
            info["types"] = {}
            for t, (raw, total) in split.items():
                final = os.path.join(work, t + ".jsonl")
                if t == "primary":
                    os.replace(raw, final)
                else:
                    measure.run([a.vbsim, "oracle", raw, "-o", final, "-q"], os.path.join(work, t + ".oracle.log"))
                    os.remove(raw)
                with open(final) as f:
                    n = sum(1 for _ in f) - 1
                info["types"][t] = {"trace": final, "rays": n, "source_rays": total}
            with open(done, "w") as f:
                json.dump(info, f, indent=1)
        sources[src] = {k: v for k, v in info.items() if k != "types"}
        for t, v in info["types"].items():
            if t in a.types:
                out[t] = dict(v, source=src)
    return out, sources


def cell_point(a, scene, rtype, trace, work):
    """The (scene, ray type) cell as a point of scripts/point_jobs.py: suite_cell.py
    writes its figures to a result file named by the measuring settings."""
    settings = {"vbsim": a.vbsim, "methods": a.methods, "testers": a.testers, "presets": a.presets,
                "bench_method": a.bench_method, "bench_repeats": a.bench_repeats, "no_bench": a.no_bench}
    key = hashlib.sha256(json.dumps(settings, sort_keys=True).encode()).hexdigest()[:10]
    settings_path = os.path.join(work, f"cell-settings-{key}.json")
    if not os.path.exists(settings_path):
        with open(settings_path, "w") as f:
            json.dump(settings, f, indent=1)
    result = os.path.join(work, f"{rtype}.result-{key}.json")
    command = [sys.executable, os.path.join(HERE, "suite_cell.py"), settings_path, scene, rtype, trace, work,
               result + ".part"]
    return point_jobs.Point(f"{scene}/{rtype}", [command], result)


def main(argv=None):
    a = parse_args(argv if argv is not None else sys.argv[1:])
    a.vbsim = os.path.abspath(a.vbsim)
    entries = scenes.load_list(a.list)
    by_name = {e["name"]: e for e in entries}
    names = [n for n in a.scenes.split(",") if n] if a.scenes else None
    chosen = scenes.select(entries, None if names else a.tier, names)
    if not chosen:
        sys.exit(f"suite: no scene of tier '{a.tier}' in {a.list}")
    started = time.monotonic()
    prepared = []
    for e in chosen:
        t0 = time.monotonic()
        meta = scenes.prepare(e, by_name, os.path.join(a.out, "scenes"), log)
        prepared.append(dict(meta, prepare_s=round(time.monotonic() - t0, 2), entry=e))
    if a.prepare_only:
        for m in prepared:
            print(f"{m['name']}: {m['triangles']} triangles, {m['bytes']} bytes, {m['ply']}")
        return 0
    if not os.path.exists(a.vbsim):
        sys.exit(f"suite: no vbsim binary at {a.vbsim} (build it, or give --vbsim)")
    cells, scene_runs = [], {}
    for meta in prepared:  # the sources run here, one scene after another; the cells as points
        work = os.path.join(a.out, "runs", meta["name"] + "-" + run_key(a, meta))
        os.makedirs(work, exist_ok=True)
        traces, sources = make_type_traces(a, meta["entry"], meta, work)
        scene_runs[meta["name"]] = sources
        for t in a.types:
            if t not in traces:
                raise SystemExit(f"suite: {meta['name']}: no {t} rays were made")
            cells.append((cell_point(a, meta["name"], t, traces[t]["trace"], work), traces[t]))
    points = [p for p, _ in cells]
    cached = {p.result for p in points if os.path.exists(p.result) and not a.fresh}
    results = []
    for (p, trace), r in zip(cells, point_jobs.run_points(points, a, os.path.join(a.out, "runs"), "suite")):
        r.update({"rays": trace["rays"], "source_rays": trace["source_rays"], "source": trace["source"],
                  "cached": p.result in cached})
        results.append(r)
    res_dir = os.path.join(a.out, "results")
    os.makedirs(res_dir, exist_ok=True)
    settings = {"size": a.size, "spp": a.spp, "glass_bounces": a.glass_bounces, "max_rays": a.max_rays,
                "ao_radius": a.ao_radius, "testers": a.testers, "methods": a.methods or "score's default",
                "presets": a.presets, "bench_method": a.bench_method, "bench_repeats": a.bench_repeats,
                "types": a.types, "tier": None if names else a.tier, "scenes": [m["name"] for m in prepared],
                "wall_s": round(time.monotonic() - started, 1), "cells": len(results),
                "cells_measured": sum(not r["cached"] for r in results)}
    page = a.page or os.path.join(res_dir, "suite.md")
    report.write_all(a.vbsim, settings, prepared, scene_runs, results, res_dir, page)
    log(f"suite: {len(results)} (scene, ray type) rows in {settings['wall_s']} s -> {res_dir}, {page}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (scenes.SceneError, measure.RunError) as err:
        sys.exit(f"suite: error: {err}")
