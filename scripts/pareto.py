#!/usr/bin/python3
"""Speed against accuracy: for every scenario family, each method's cost against
its error rate, one chart per family with one panel per cost axis, and the
Pareto front (methods no other method beats on both cost and error) marked.

    /usr/bin/python3 scripts/pareto.py [--score build/results/accuracy.json]
        [--tester three-half-plane] [--out docs/results]

Input: the JSON table of `vbsim score --out` (rows per family, method, tester
and ray kind), the one table that holds both the error rates and, from
`vbsim score --mode cycle`, the cycle-level costs of the same traces. Cost
axes, lower is better on each:
  - operations per ray: each ray's emission operations (those of the parts
    that act on its kind of ray) + candidate x candidates/ray + suspect x
    suspects/ray, the counts of model/datapath/method_costs.cpp with the
    candidates and suspects measured in the run (the row's `ops_per_ray`);
  - the method's own energy per ray (pJ; the row's `energy.method_per_ray_pj`,
    priced by the technology file: docs/energy.md), present in tables made
    since the energy model;
  - bits per ray in flight (the ray record the hardware holds);
  - functional replay time per ray (microseconds; from rays per second; it
    includes the exact verdicts, which cost more for wrong answers);
  - cycles per ray of the cycle-level model (the `cycle` object of the `all`
    rows, present when the table was made in cycle mode);
  - from the same cycle-level runs (tables made since they carry them): the
    energy per ray with memory and leakage (`cycle.energy_per_ray_pj`) and the
    chip's area (`cycle.chip_mm2`, an area chart).
Each chart's title names its workload (the family), the hardware preset and the
technology file; every error rate carries its 95% Wilson interval (the
secondary row's `errors.per_million` lower and upper).
Error rate: (self_hit + false_hit + missed) / scored secondary rays (every ray
that leaves a surface; camera rays are not what the methods are about).
Output: OUT/pareto-FAMILY.png and OUT/pareto.md (generated).
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ERROR_KINDS = ("self_hit", "false_hit", "missed")


def ops_per_ray(row):
    """The method's operations per ray (method_costs.h) from a `vbsim score` row."""
    if "ops_per_ray" in row:
        return row["ops_per_ray"]
    cost, av, rays = row["config"]["cost_ops"], row["avoidance"], row["rays"]
    total = cost["emission"] * rays + cost["candidate"] * av["candidates"] + cost["suspect"] * av["suspects"]
    return total / rays if rays else 0.0


def error_rate(row):
    n = row["scored"]
    return sum(row["counts"][k] for k in ERROR_KINDS) / n if n else 0.0


def points_of(rows, family, tester):
    """One point per method of a family: its secondary-ray error rate and costs."""
    secondary = {r["method"]: r for r in rows
                 if r["family"] == family and r["tester"] == tester and r["kind"] == "secondary"}
    out = []
    for r in rows:
        if r["family"] != family or r["tester"] != tester or r["kind"] != "all":
            continue
        sec = secondary.get(r["method"])
        if sec is None:
            sys.exit(f"pareto: no secondary row for {family} / {r['method']} / {tester}: "
                     "regenerate the table with this vbsim")
        pm = sec["errors"]["per_million"]
        p = {"method": r["method"], "error": error_rate(sec), "scored": sec["scored"],
             "lower": pm["lower"] / 1e6, "upper": pm["upper"] / 1e6,
             "errors": sum(sec["counts"][k] for k in ERROR_KINDS),
             "ops": ops_per_ray(r), "bits": r["config"]["bits_per_ray"],
             "us": 1e6 / r["rays_per_s"] if r.get("rays_per_s") else float("nan")}
        if "cycle" in r:
            p["cycles"] = r["cycle"]["cycles_per_ray"]
            p["preset"] = r["cycle"]["preset"]
            if "energy_per_ray_pj" in r["cycle"]:
                p["pj_total"] = r["cycle"]["energy_per_ray_pj"]
                p["mm2"] = r["cycle"]["chip_mm2"]
        if "energy" in r:
            p["pj"] = r["energy"]["method_per_ray_pj"]
            p["tech"] = os.path.basename(r["energy"]["tech"])
        out.append(p)
    return out


def pareto_front(points, cost):
    """Methods that no other method beats on both `cost` and error (ties kept)."""
    front = []
    for p in points:
        dominated = any(q[cost] <= p[cost] and q["error"] <= p["error"]
                        and (q[cost] < p[cost] or q["error"] < p["error"]) for q in points)
        if not dominated:
            front.append(p)
    return sorted(front, key=lambda p: p[cost])


AXES = [("ops", "operations per ray (method only)"), ("pj", "energy per ray, pJ (method only)"),
        ("bits", "bits per ray in flight"),
        ("us", "functional replay, microseconds per ray"), ("cycles", "cycles per ray, cycle-level model"),
        ("pj_total", "energy per ray, pJ (cycle-level: operations, memory, leakage)"),
        ("mm2", "chip area, mm2 (cycle-level model)")]


def chart_title(family, points):
    """The workload, the hardware preset and the technology file of a family's chart."""
    presets = sorted({p["preset"] for p in points if "preset" in p})
    techs = sorted({p["tech"] for p in points if "tech" in p})
    return (f"Speed against accuracy: {family}; preset {', '.join(presets) or 'none (functional)'}; "
            f"technology {', '.join(techs) or 'n/a'} (red: Pareto front; bars: 95% Wilson intervals)")


def plot_family(family, points, path):
    """One panel per cost axis; each method keeps its colour and marker across
    panels, named once in a legend under the panels."""
    axes = [(k, label) for k, label in AXES if any(k in p for p in points)]
    fig, panels = plt.subplots(1, len(axes), figsize=(4.6 * len(axes), 5.4), dpi=100, squeeze=False)
    floor = 0.3 / max(max(p["scored"] for p in points), 1)
    lowest = min([p["error"] for p in points if p["error"] > 0] + [1.0])
    colours = plt.get_cmap("tab20").colors
    markers = "osD^v<>phX*"
    for ax, (key, label) in zip(panels[0], axes):
        for i, p in enumerate(points):
            if key not in p:  # a method the cycle-level runs did not measure
                continue
            y = max(p["error"], floor)
            ax.errorbar(p[key], y, yerr=[[y - max(p["lower"], floor / 2)], [max(p["upper"], y) - y]], fmt="none",
                        ecolor=colours[i % 20], elinewidth=0.8, capsize=2, zorder=2)
            ax.scatter(p[key], y, s=28, color=colours[i % 20],
                       marker=markers[i % len(markers)], zorder=3, label=p["method"])
        front = pareto_front([p for p in points if key in p], key)
        ax.step([p[key] for p in front], [max(p["error"], floor) for p in front], where="post",
                color="tab:red", linewidth=1.0, zorder=2)
        ax.axhline(floor, color="0.6", linewidth=0.8, linestyle=":")
        ax.set_yscale("log")
        ax.set_ylim(min(floor, lowest) / 2, 1.5)
        if key in ("us", "cycles"):
            ax.set_xscale("log")
        ax.set_xlabel(label)
        ax.grid(True, linewidth=0.4, alpha=0.5)
    panels[0][0].set_ylabel("errors per secondary ray (dotted line: no error)")
    handles, labels = panels[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7, frameon=False)
    fig.suptitle(chart_title(family, points), fontsize=10)
    fig.tight_layout(rect=(0, 0.2, 1, 1))
    fig.savefig(path)
    plt.close(fig)
    return [k for k, _ in axes]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--score", default=os.path.join(ROOT, "build", "results", "accuracy.json"))
    ap.add_argument("--tester", default="three-half-plane")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "results"))
    args = ap.parse_args()
    if not os.path.exists(args.score):
        sys.exit(f"pareto: {args.score} not found: run scripts/make_results.sh (or vbsim score --out) first")
    with open(args.score) as f:
        score = json.load(f)
    rows = score["rows"]
    presets = sorted({r["cycle"]["preset"] for r in rows if "cycle" in r})
    families = sorted({r["family"] for r in rows})
    os.makedirs(args.out, exist_ok=True)
    lines = ["# Speed against accuracy", "",
             "Generated by `scripts/pareto.py` from the table of `vbsim score` "
             "(`scripts/make_results.sh` runs both); do not edit by hand.", "",
             f"Tester: {args.tester}. Error rate: (self_hit + false_hit + missed) per scored secondary "
             "ray (every ray that leaves a surface). Costs, lower is better: operations per ray of the "
             "method itself (`docs/methods.md`, with the candidates and suspects each scenario really "
             "produces), the method's own energy per ray (`docs/energy.md`: its operations and extra "
             "record bits priced by the technology file), bits per ray in flight, functional replay "
             "time per ray, and the cycle-level "
             f"model's cycles per ray, energy per ray (operations, memory, leakage) and chip area "
             f"({', '.join(presets) or 'not measured'} preset), all from the one "
             f"table `{score['command']}` wrote. The Pareto front holds the methods that no other method "
             "beats on both the cost and the error rate. Each chart's title names its workload, preset "
             "and technology file; the bars are the error rates' 95% Wilson intervals.", ""]
    for family in families:
        points = points_of(rows, family, args.tester)
        if not points:
            continue
        name = f"pareto-{family}.png"
        keys = plot_family(family, points, os.path.join(args.out, name))
        lines += [f"## {family}", "", f"![{family}]({name})", ""]
        for key, label in AXES:
            if key in keys:
                front = ", ".join(f"`{p['method']}` ({p[key]:.3g}, {p['errors']} errors)"
                                  for p in pareto_front([p for p in points if key in p], key))
                lines.append(f"- front on {label}: {front}")
        lines.append("")
    with open(os.path.join(args.out, "pareto.md"), "w") as f:
        f.write("\n".join(lines))
    print(f"pareto: wrote {len(families)} charts and pareto.md in {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
