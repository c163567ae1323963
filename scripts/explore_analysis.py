"""The comparisons of an exploration's rows (docs/explore.md): the best design
of each method within an area budget (iso-area), the smallest and the most
frugal design of each method reaching a throughput (iso-throughput), and each
knob's main effect on each method's costs (sensitivity).
"""
import math
import statistics


def by(rows, *keys):
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r[k] for k in keys), []).append(r)
    return groups


def default_budgets(rows):
    """Area budgets where a comparison says something: the smallest area at which every
    method has a design, and the largest area of any design (everything fits)."""
    per_method = by(rows, "method")
    floor = max(min(r["area_mm2"] for r in g) for g in per_method.values())
    top = max(r["area_mm2"] for r in rows)
    return sorted({round(floor * 1.0001, 4), round(top * 1.0001, 4)})


def default_targets(rows):
    """Throughput targets: half and nine tenths of the best any design of any method reaches."""
    best = max(r["mrays_per_s"] for r in rows)
    return [round(best * 0.5, 3), round(best * 0.9, 3)]


def iso_area(rows, budgets):
    """Per workload, technology and budget: each method's fastest design within the budget (None: none fits)."""
    out = []
    for (workload, tech), group in by(rows, "workload", "tech").items():
        for budget in budgets:
            best = {}
            for method, mrows in by(group, "method").items():
                fits = [r for r in mrows if r["area_mm2"] <= budget]
                best[method[0]] = max(fits, key=lambda r: (r["mrays_per_s"], -r["area_mm2"])) if fits else None
            out.append({"workload": workload, "tech": tech, "budget_mm2": budget, "best": best})
    return out


def iso_throughput(rows, targets):
    """Per workload, technology and target: each method's smallest design reaching it, and its least energy."""
    out = []
    for (workload, tech), group in by(rows, "workload", "tech").items():
        for target in targets:
            smallest, frugal = {}, {}
            for method, mrows in by(group, "method").items():
                fast = [r for r in mrows if r["mrays_per_s"] >= target]
                smallest[method[0]] = min(fast, key=lambda r: (r["area_mm2"], -r["mrays_per_s"])) if fast else None
                frugal[method[0]] = min(fast, key=lambda r: r["energy_pj_per_ray"]) if fast else None
            out.append({"workload": workload, "tech": tech, "target": target, "smallest": smallest,
                        "frugal": frugal})
    return out


def sensitivity(rows, knobs, cost):
    """Per method: each knob's main effect on `cost`, the spread (max - min) of the cost's mean
    over the designs at each of the knob's values, as a fraction of the cost's mean; averaged
    over workloads and technology files. Knobs with one value in the rows are left out."""
    out = {}
    for method, mrows in by(rows, "method").items():
        effects = {}
        for knob in knobs:
            spreads = []
            for _, group in by(mrows, "workload", "tech").items():
                values = by(group, knob)
                if len(values) < 2:
                    continue
                means = [statistics.fmean(r[cost] for r in g) for g in values.values()]
                overall = statistics.fmean(r[cost] for r in group)
                if overall > 0 and all(math.isfinite(x) for x in means):
                    spreads.append((max(means) - min(means)) / overall)
            if spreads:
                effects[knob] = statistics.fmean(spreads)
        out[method[0]] = effects
    return out


def method_errors(rows):
    """Per workload and method: the secondary error rate and interval, and whether every design agrees
    (they must: the hits do not depend on the design)."""
    out = {}
    for (workload, method), group in by(rows, "workload", "method").items():
        rates = {(r["errors_per_million"], r["secondary_scored"]) for r in group
                 if not math.isnan(r["errors_per_million"])}
        r = group[0]
        out[(workload, method)] = {"errors_per_million": r["errors_per_million"], "ci95_low": r["ci95_low"],
                                   "ci95_high": r["ci95_high"], "scored": r["secondary_scored"],
                                   "unscored": r["secondary_unscored"],
                                   "camera": r["camera_errors_per_million"], "consistent": len(rates) <= 1}
    return out
