"""The workload suite's outputs from its measured rows (docs/suite.md):
suite.json (everything), suite.csv (one row per scene, ray type, method and
tester), suite-speed.csv (one row per scene and ray type: speeds and peak
memory), suite.png (cycles per ray and errors by scene and type) and the
markdown page. Every figure comes from the rows; nothing is computed twice."""
import csv
import json
import os
import shutil

from provenance import csv_comment, provenance_comment, script_provenance, stamp_png

METHOD_COLUMNS = ("scene", "type", "kind", "method", "tester", "rays", "errors", "self_hit", "false_hit", "missed",
                  "rate", "lower", "upper")
PRESET_FIELDS = ("cycles_per_ray", "energy_per_ray_pj", "chip_mm2")
SPEED_COLUMNS = ("scene", "type", "rays", "functional_rays_per_s", "embree_rays_per_s", "functional_ratio",
                 "cycle_rays_per_s", "cycle_embree_rays_per_s", "cycle_ratio", "peak_rss_mb_score",
                 "peak_rss_mb_bench", "peak_rss_mb_source", "score_wall_s")


def method_rows(results, presets):
    for r in results:
        for m in r["methods"]:
            row = {"scene": r["scene"], "type": r["type"]}
            row.update({k: m[k] for k in METHOD_COLUMNS if k in m})
            for p in presets:
                for f in PRESET_FIELDS:
                    row[f"{f}_{p}"] = m.get(p, {}).get(f)
            yield row


def speed_row(r, scene_runs):
    runs = r["runs"]
    fun, cyc = runs.get("bench-functional", {}), runs.get("bench-cycle", {})
    scores = [v for k, v in runs.items() if k.startswith("score-")]
    src = scene_runs.get(r["scene"], {}).get(r["source"], {})
    return {"scene": r["scene"], "type": r["type"], "rays": r["rays"],
            "functional_rays_per_s": fun.get("vbsim_rays_per_s"), "embree_rays_per_s": fun.get("embree_rays_per_s"),
            "functional_ratio": fun.get("ratio"), "cycle_rays_per_s": cyc.get("vbsim_rays_per_s"),
            "cycle_embree_rays_per_s": cyc.get("embree_rays_per_s"), "cycle_ratio": cyc.get("ratio"),
            "peak_rss_mb_score": max((s["peak_rss_mb"] or 0 for s in scores), default=None),
            "peak_rss_mb_bench": max((b.get("peak_rss_mb") or 0 for b in (fun, cyc) if b), default=None),
            "peak_rss_mb_source": src.get("peak_rss_mb"),
            "score_wall_s": round(sum(s["wall_s"] for s in scores), 2)}


def _write_csv(path, rows, columns, prov):
    with open(path + ".partial", "w", newline="") as f:
        f.write(csv_comment(prov))
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for row in rows:
            w.writerow({k: f"{v:.7g}" if isinstance(v, float) else v for k, v in row.items()})
    os.replace(path + ".partial", path)


def _fmt(x, digits=0):
    if x is None:
        return "-"
    if isinstance(x, float) and digits:
        return f"{x:,.{digits}f}"
    return f"{round(x):,}"


def _per_million(m):
    return f"{m['rate'] * 1e6:,.0f} [{m['lower'] * 1e6:,.0f}, {m['upper'] * 1e6:,.0f}]"


def write_all(vbsim, settings, prepared, scene_runs, results, res_dir, page):
    inputs = [m["ply"] for m in prepared]
    prov = script_provenance(vbsim, inputs)
    presets = settings["presets"]
    doc = {"settings": settings, "scenes": [{k: v for k, v in m.items() if k != "entry"} | {
        "package": m["entry"]["package"], "licence": m["entry"]["licence"], "surface": m["entry"]["surface"],
        "listed_triangles": m["entry"]["triangles"], "origin": m["entry"]["origin"]} for m in prepared],
        "sources": scene_runs, "results": results, "provenance": prov}
    with open(os.path.join(res_dir, "suite.json.partial"), "w") as f:
        json.dump(doc, f, indent=1)
    os.replace(os.path.join(res_dir, "suite.json.partial"), os.path.join(res_dir, "suite.json"))
    columns = list(METHOD_COLUMNS) + [f"{f}_{p}" for p in presets for f in PRESET_FIELDS]
    _write_csv(os.path.join(res_dir, "suite.csv"), method_rows(results, presets), columns, prov)
    speeds = [speed_row(r, scene_runs) for r in results]
    _write_csv(os.path.join(res_dir, "suite-speed.csv"), speeds, SPEED_COLUMNS, prov)
    page_dir = os.path.dirname(os.path.abspath(page))
    stem = os.path.splitext(os.path.basename(page))[0]  # suite.md: suite.csv, suite-speed.csv, suite.png
    if page_dir != os.path.abspath(res_dir) or stem != "suite":  # the CSVs beside a page kept elsewhere
        for name, to in (("suite.csv", f"{stem}.csv"), ("suite-speed.csv", f"{stem}-speed.csv")):
            shutil.copyfile(os.path.join(res_dir, name), os.path.join(page_dir, to))
    chart = os.path.join(page_dir, f"{stem}.png")
    drew = _chart(results, settings, chart, prov)
    _page(page, settings, doc, speeds, presets, prov, drew and os.path.basename(chart))


def _chart(results, settings, path, prov):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return False
    method = settings["bench_method"]
    scenes_ = list(dict.fromkeys(r["scene"] for r in results))
    types = list(dict.fromkeys(r["type"] for r in results))
    preset = settings["presets"][0]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    width = 0.8 / max(1, len(scenes_))
    for i, s in enumerate(scenes_):
        cyc, err = [], []
        for t in types:
            r = next((r for r in results if r["scene"] == s and r["type"] == t), None)
            m = next((m for m in (r["methods"] if r else []) if m["method"] == method), None)
            cyc.append(m.get(preset, {}).get("cycles_per_ray", 0) if m else 0)
            err.append(m["rate"] * 1e6 if m else 0)
        xs = [k + i * width for k in range(len(types))]
        axes[0].bar(xs, cyc, width, label=s)
        axes[1].bar(xs, err, width, label=s)
    for ax, title in ((axes[0], f"cycles per ray, {preset} preset ({method})"),
                      (axes[1], f"errors per million rays ({method})")):
        ax.set_xticks([k + 0.4 - width / 2 for k in range(len(types))])
        ax.set_xticklabels(types, rotation=30, ha="right")
        ax.set_title(title, fontsize=10)
    axes[0].set_yscale("log")
    axes[1].set_yscale("symlog", linthresh=100)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path + ".partial.png", dpi=90)
    plt.close(fig)
    os.replace(path + ".partial.png", path)
    stamp_png(path, prov)
    return True


def _by_kind_section(results):
    """The `pathtracer` type split by the kinds its capture gave its rays: per
    scene, each method's errors per million on each kind's rays."""
    if not results:
        return []
    L = ["", "## The `pathtracer` rays by kind", "",
         "Embree's path tracer captured: its rays split by the kind `vbsim capture` gave each (docs/capture.md, "
         "\"Parent links and kinds\"): camera rays, shadow rays (occlusion queries toward the light), and the "
         "bounces by the direction they leave in. Errors per million with 95% Wilson intervals, rays in brackets."]
    for r in results:
        kinds = list(dict.fromkeys(m["kind"] for m in r["by_kind"]))
        count = {k: next(m["rays"] for m in r["by_kind"] if m["kind"] == k) for k in kinds}
        L += ["", f"### {r['scene']}", "", "| method | tester | " +
              " | ".join(f"{k} ({count[k]:,})" for k in kinds) + " |", "|---|---|" + "---:|" * len(kinds)]
        for method, tester in dict.fromkeys((m["method"], m["tester"]) for m in r["by_kind"]):
            cells = []
            for k in kinds:
                m = next((m for m in r["by_kind"] if (m["method"], m["tester"], m["kind"]) == (method, tester, k)),
                         None)
                cells.append(_per_million(m) if m else "-")
            L.append(f"| `{method}` | {tester} | " + " | ".join(cells) + " |")
    return L


def _page(path, settings, doc, speeds, presets, prov, chart):
    stem = os.path.splitext(os.path.basename(path))[0]
    s = settings
    busy = sum(v["wall_s"] for r in doc["results"] for v in r["runs"].values()) + \
        sum(v["wall_s"] for runs in doc["sources"].values() for v in runs.values())
    kept = "all rays of each type" if not s["max_rays"] else f"at most {s['max_rays']:,} rays a type, taken evenly"
    L = ["# Workload suite", "",
         "Generated by `scripts/suite.py` (docs/suite.md); do not edit by hand. Every figure below is",
         "one run's on the machine that ran it (speeds, memory) or simulated (cycles, energy, area).", "",
         "## This run", "",
         f"- command: `{' '.join(['scripts/suite.py'] + prov['command'][2:])}`",
         f"- frame {s['size']} for the renders (every pixel sampled: one primary ray a pixel in the mirror render, "
         f"{s['spp']} path(s) a pixel in the path tracer), up to {s['glass_bounces']} refractions and reflections a path in the glass render, "
         f"{kept}; "
         f"ambient-occlusion rays {s['ao_radius']} of the bounding-box diagonal long",
         f"- methods: {s['methods']}; testers: {s['testers']}; cycle-level presets: {', '.join(presets)}; "
         f"speed runs with `{s['bench_method']}` (vbsim bench, one thread, best of {s['bench_repeats']})",
         f"- wall time of this invocation: {s['wall_s']:,} s, {s['cells_measured']} of its {s['cells']} (scene, ray type) "
         "cells measured in it (the others from an earlier run of the same settings and vbsim binary, "
         f"`OUT/runs`); the renders', scores' and benches' wall times summed over all cells: {busy:,.0f} s "
         "(each command's own in `suite.json`)", "",
         "## Scenes", "",
         "| scene | triangles | vertices | surface | boundary edges | package | licence |",
         "|---|---:|---:|---|---:|---|---|"]
    for m in doc["scenes"]:
        L.append(f"| {m['name']} | {m['triangles']:,} | {m['vertices']:,} | {m['surface']} | {m['boundary_edges']:,} | "
                 f"{m['package']} | {m['licence']} |")
    results = doc["results"]
    L += ["", "## Rays per scene and type", "",
          "Rays scored (the type's rays in its source, in brackets, when fewer were kept).", ""]
    types = list(dict.fromkeys(r["type"] for r in results))
    L.append("| scene | " + " | ".join(types) + " |")
    L.append("|---|" + "---:|" * len(types))
    for sc in dict.fromkeys(r["scene"] for r in results):
        cells = []
        for t in types:
            r = next((r for r in results if r["scene"] == sc and r["type"] == t), None)
            cells.append("-" if r is None else (f"{r['rays']:,}" if r["rays"] == r["source_rays"]
                                                else f"{r['rays']:,} ({r['source_rays']:,})"))
        L.append(f"| {sc} | " + " | ".join(cells) + " |")
    bm = s["bench_method"]
    L += ["", f"## Cost per ray and speed (`{bm}`)", "",
          "Cycles and energy per ray (all of it: operations, memory and leakage) and the chip's area from "
          "`vbsim score --mode cycle`; vbsim's rays/s and its ratio to Embree's `rtcIntersect1`/`rtcOccluded1` on "
          "the same rays from `vbsim bench --trace` (functional and cycle-level); peak resident set of the score "
          "and bench runs (`/usr/bin/time -v`).", ""]
    head = ["scene", "type", "rays"] + [f"cycles/ray {p}" for p in presets] + [f"pJ/ray {p}" for p in presets] + \
           [f"mm2 {p}" for p in presets] + ["functional rays/s", "/ Embree", "cycle rays/s", "/ Embree", "peak MB"]
    L.append("| " + " | ".join(head) + " |")
    L.append("|---|---|" + "---:|" * (len(head) - 2))
    for r, sp in zip(results, speeds):
        m = next((m for m in r["methods"] if m["method"] == bm), r["methods"][0])
        cells = [r["scene"], r["type"], f"{r['rays']:,}"]
        cells += [_fmt(m.get(p, {}).get("cycles_per_ray"), 1) for p in presets]
        cells += [_fmt(m.get(p, {}).get("energy_per_ray_pj")) for p in presets]
        cells += [_fmt(m.get(p, {}).get("chip_mm2"), 2) for p in presets]
        ratio = lambda x: "-" if x is None else f"{x:.3f}"  # noqa: E731
        cells += [_fmt(sp["functional_rays_per_s"]), ratio(sp["functional_ratio"]), _fmt(sp["cycle_rays_per_s"]),
                  ratio(sp["cycle_ratio"]),
                  _fmt(max(x or 0 for x in (sp["peak_rss_mb_score"], sp["peak_rss_mb_bench"])))]
        L.append("| " + " | ".join(cells) + " |")
    if chart:
        L += ["", f"![cycles per ray and errors by scene and ray type]({chart})"]
    L += ["", "## Every method's errors per million rays, 95% Wilson intervals", "",
          "Secondary rays: self hits, false hits and misses against the exact answer; primary rays: camera "
          "rays answered wrong (missed or a false hit; a camera ray has no surface to re-hit). Per ray type, one column per scene; the full table (counts, cycles, energy and area on "
          f"each preset for every method) is in `{stem}.csv` beside this page."]
    for t in types:
        rows_t = [r for r in results if r["type"] == t]
        sc = [r["scene"] for r in rows_t]
        L += ["", f"### {t}", "", "| method | tester | " + " | ".join(sc) + " |", "|---|---|" + "---:|" * len(sc)]
        keys = list(dict.fromkeys((m["method"], m["tester"]) for r in rows_t for m in r["methods"]))
        for method, tester in keys:
            cells = []
            for r in rows_t:
                m = next((m for m in r["methods"] if (m["method"], m["tester"]) == (method, tester)), None)
                cells.append(_per_million(m) if m else "-")
            L.append(f"| `{method}` | {tester} | " + " | ".join(cells) + " |")
    L += _by_kind_section([r for r in results if r.get("by_kind")])
    L += ["", provenance_comment(prov).rstrip("\n")]
    with open(path + ".partial", "w") as f:
        f.write("\n".join(L) + "\n")
    os.replace(path + ".partial", path)
