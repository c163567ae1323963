"""Charts and breakdown points of a stability sweep (used by sweep.py).

A row is one (sweep point x, method) with the summed verdict counts of its
secondary rays (`rays` and the verdicts) and, apart, its camera rays and the
camera rays its tester missed. The error rate of a row is (self_hit +
false_hit + missed) / scored secondary rays. A sweep definition's
`hard` says which end of its parameter is the difficult one ("low" or "high");
a method's breakdown point is the easiest value at which it makes an error.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ERROR_KINDS = ("self_hit", "false_hit", "missed")


def scored(row):
    return row["rays"] - row["unscored"]


def errors(row):
    return sum(row[k] for k in ERROR_KINDS)


def error_rate(row):
    n = scored(row)
    return errors(row) / n if n else 0.0


def format_x(sweep, x):
    unit = sweep.get("unit", "")
    text = f"{x:.3g}" if isinstance(x, float) else str(x)
    return f"{text} {unit}".strip()


def rows_of(rows, method):
    return sorted((r for r in rows if r["method"] == method), key=lambda r: r["x"])


def plot_sweep(sweep, rows, path):
    """One line per method: errors per scored ray against the parameter.
    Points without an error sit on a floor line below the smallest rate that a
    single error could give."""
    fig, ax = plt.subplots(figsize=(7.5, 4.5), dpi=110)
    most = max((scored(r) for r in rows), default=1) or 1
    floor = 0.3 / most
    markers = "os^vD<>px*h"
    for i, method in enumerate(m["label"] for m in sweep["methods"]):
        mr = rows_of(rows, method)
        xs = [r["x"] for r in mr]
        ys = [max(error_rate(r), floor) for r in mr]
        ax.plot(xs, ys, marker=markers[i % len(markers)], markersize=4, linewidth=1.2,
                label=method)
    ax.axhline(floor, color="0.6", linewidth=0.8, linestyle=":")
    ax.text(0.01, floor, " no error", transform=ax.get_yaxis_transform(), va="bottom",
            fontsize=7, color="0.4")
    if sweep.get("xlog"):
        ax.set_xscale("log", base=sweep.get("xbase", 10))
    elif "symlog" in sweep:  # a range that starts at 0: linear below the threshold
        ax.set_xscale("symlog", linthresh=sweep["symlog"])
    ax.set_yscale("log")
    ax.set_ylim(floor / 2, 1.5)
    ax.set_xlabel(sweep["xlabel"])
    ax.set_ylabel("errors per secondary ray (self hit + false hit + missed)")
    ax.set_title(sweep["title"], fontsize=10)
    ax.grid(True, which="major", linewidth=0.4, alpha=0.5)
    ax.legend(fontsize=7, loc="best", ncol=2)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def breakdown_point(sweep, mr):
    """Where a method that fails somewhere starts to fail, in words. `hard`:
    "low" or "high" (the difficult end), or "both" (errors at both ends: the
    error-free window is what matters)."""
    hard = sweep.get("hard", "low")
    ok = [r for r in mr if errors(r) == 0]
    failing = [r for r in mr if errors(r) > 0]
    if hard == "both":
        if not ok:
            return "fails at every point"
        lo, hi = ok[0]["x"], ok[-1]["x"]
        window = all(errors(r) == 0 for r in mr if lo <= r["x"] <= hi)
        return (f"error-free from {format_x(sweep, lo)} to {format_x(sweep, hi)}"
                + ("" if window else " (with errors inside that range)"))
    hard_low = hard == "low"
    point = max(failing, key=lambda r: r["x"]) if hard_low else min(failing, key=lambda r: r["x"])
    beyond = [r for r in mr if (r["x"] <= point["x"] if hard_low else r["x"] >= point["x"])]
    side = "and below" if hard_low else "and above"
    return format_x(sweep, point["x"]) + (f" {side}" if all(errors(r) > 0 for r in beyond)
                                          else " (errors not monotone)")


def breakdown_text(sweep, rows):
    """Markdown lines: per method, where it fails and how."""
    lines = ["| method | breakdown point | points with errors | worst rate | self_hit / false_hit / missed (all points) "
             "| camera rays missed |",
             "|---|---|---|---|---|---|"]
    for method in (m["label"] for m in sweep["methods"]):
        mr = rows_of(rows, method)
        failing = [r for r in mr if errors(r) > 0]
        totals = " / ".join(str(sum(r[k] for r in mr)) for k in ERROR_KINDS)
        camera = (f"{sum(r.get('camera_missed', 0) for r in mr)} of "
                  f"{sum(r.get('camera_rays', 0) for r in mr)}")
        if not failing:
            n = sum(scored(r) for r in mr)
            lines.append(f"| {method} | holds over the whole range ({n} scored secondary rays) | 0 of {len(mr)} "
                         f"| 0 | {totals} | {camera} |")
            continue
        worst = max(failing, key=error_rate)
        where = breakdown_point(sweep, mr)
        lines.append(f"| {method} | {where} | {len(failing)} of {len(mr)} | "
                     f"{error_rate(worst):.3g} at {format_x(sweep, worst['x'])} | {totals} | {camera} |")
    return lines
