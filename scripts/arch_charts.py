"""Charts of the architecture study (used by arch_sweep.py).

A row is one sweep point: {"sweep", "series", "x"} plus the figures of
arch_points.summarise(). Each function draws the sweeps of one figure (a group)
and writes a PNG.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from arch_points import MEMORY_STALLS, STALL_CAUSES  # noqa: E402

STALL_LABELS = {"memory_wait": "memory wait", "box_pipeline_full": "box issue wait",
                "triangle_pipeline_full": "triangle issue wait",
                "avoidance_pipeline_full": "avoidance issue wait", "stack_refill_wait": "stack refill"}
MARKERS = "os^vD<>p"


def series_rows(rows, sweep, label):
    return sorted((r for r in rows if r["sweep"] == sweep["name"] and r["series"] == label),
                  key=lambda r: r["x"])


def x_values(sweep, rs):
    scale = sweep.get("xscale", 1)
    return [r["x"] / scale for r in rs]


def style_x(ax, sweep, xs):
    if sweep.get("xlog"):
        ax.set_xscale("log", base=2)
        ax.set_xticks(xs)
        ax.set_xticklabels([f"{x:g}" for x in xs], fontsize=7)
        ax.minorticks_off()
    ax.set_xlabel(sweep["xlabel"])
    ax.grid(True, linewidth=0.4, alpha=0.5)


def draw_throughput(ax, sweep, rows):
    """Rays per cycle per series; a series marked `bound` also gets its analytic bound."""
    xs = []
    for i, s in enumerate(sweep["series"]):
        rs = series_rows(rows, sweep, s["label"])
        xs = x_values(sweep, rs)
        line, = ax.plot(xs, [r["rays_per_cycle"] for r in rs], marker=MARKERS[i % len(MARKERS)],
                        markersize=4, linewidth=1.2, label=s["label"])
        if s.get("bound"):
            ax.plot(xs, [r["bound"] for r in rs], linestyle="--", linewidth=1, color=line.get_color(),
                    label="analytic bound (" + s["label"] + ")")
    style_x(ax, sweep, xs)
    ax.set_ylabel("rays per cycle")
    ax.set_ylim(bottom=0)
    ax.set_title(sweep["title"], fontsize=9)


def plot_lines(sweeps, rows, path):
    fig, axes = plt.subplots(1, len(sweeps), figsize=(4.6 * len(sweeps) + 1.4, 4.2), dpi=110, squeeze=False)
    for ax, sweep in zip(axes[0], sweeps):
        draw_throughput(ax, sweep, rows)
    axes[0][0].legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def plot_cache(sweeps, rows, path):
    """Rays per cycle (left axis) and the swept cache's hit rate (right axis)."""
    fig, axes = plt.subplots(1, len(sweeps), figsize=(5.2 * len(sweeps), 4.2), dpi=110, squeeze=False)
    for ax, sweep in zip(axes[0], sweeps):
        draw_throughput(ax, sweep, rows)
        right = ax.twinx()
        for s in sweep["series"]:
            rs = series_rows(rows, sweep, s["label"])
            right.plot(x_values(sweep, rs), [r[sweep["hit_rate"]] for r in rs], color="C3",
                       linestyle=":", marker="x", markersize=4, label=sweep["hit_rate"].replace("_", " "))
        right.set_ylim(0, 1.02)
        right.set_ylabel("hit rate", color="C3")
        lines = ax.get_legend_handles_labels()
        more = right.get_legend_handles_labels()
        ax.legend(lines[0] + more[0], lines[1] + more[1], fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def draw_stall_bars(ax, sweep, rows, label):
    """Stacked bars: each stall cause's share of slot-cycles, per x, for one series."""
    rs = series_rows(rows, sweep, label)
    pos = np.arange(len(rs))
    bottom = np.zeros(len(rs))
    for k, cause in enumerate(STALL_CAUSES):
        shares = np.array([r["stall_shares"][cause] for r in rs])
        if shares.any():
            ax.bar(pos, shares, bottom=bottom, color=f"C{k}", label=STALL_LABELS[cause])
            bottom += shares
    ax.set_xticks(pos)
    ax.set_xticklabels([f"{x:g}" for x in x_values(sweep, rs)], fontsize=7)
    ax.set_xlabel(sweep["xlabel"])
    ax.set_ylim(0, 1)
    ax.set_ylabel("share of slot-cycles")
    ax.set_title(f"stalls, {label}", fontsize=8)
    ax.legend(fontsize=6, loc="upper left")


def draw_memory_stall_bars(ax, sweep, rows, label):
    """Stacked bars: memory-side wait cycles per line request by cause, for one series."""
    rs = series_rows(rows, sweep, label)
    pos = np.arange(len(rs))
    bottom = np.zeros(len(rs))
    for k, cause in enumerate(MEMORY_STALLS):
        cycles = np.array([r["memory_stalls_per_line"].get(cause, 0.0) for r in rs])
        if cycles.any():
            ax.bar(pos, cycles, bottom=bottom, color=f"C{k + 5}", label=cause.replace("_", " "))
            bottom += cycles
    ax.set_xticks(pos)
    ax.set_xticklabels([f"{x:g}" for x in x_values(sweep, rs)], fontsize=7)
    ax.set_xlabel(sweep["xlabel"])
    ax.set_yscale("symlog", linthresh=1)
    ax.set_ylabel("memory wait cycles per line request")
    ax.set_title(f"memory-side waits, {label}", fontsize=8)
    ax.legend(fontsize=6, loc="upper left")


def plot_stalls(sweeps, rows, path):
    """Top: rays per cycle; middle: slot stalls and bottom: memory-side waits of the
    sweep's `bars` series."""
    fig, axes = plt.subplots(3, len(sweeps), figsize=(5.2 * len(sweeps), 10.5), dpi=110, squeeze=False)
    for col, sweep in enumerate(sweeps):
        draw_throughput(axes[0][col], sweep, rows)
        axes[0][col].legend(fontsize=7, loc="best")
        bars = sweep.get("bars", sweep["series"][0]["label"])
        draw_stall_bars(axes[1][col], sweep, rows, bars)
        draw_memory_stall_bars(axes[2][col], sweep, rows, bars)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def plot_methods(sweeps, rows, path):
    """Per method: cycles per ray (total cycles / rays), mean ray latency and bits per ray."""
    sweep = sweeps[0]
    methods = sweep["values"]
    fig, axes = plt.subplots(3, 1, figsize=(9, 10), dpi=110, sharex=True)
    pos = np.arange(len(methods))
    width = 0.8 / len(sweep["series"])
    for i, s in enumerate(sweep["series"]):
        by_method = {r["x"]: r for r in rows if r["sweep"] == sweep["name"] and r["series"] == s["label"]}
        off = pos - 0.4 + width * (i + 0.5)
        axes[0].bar(off, [by_method[m]["cycles_per_ray"] for m in methods], width, label=s["label"])
        axes[1].bar(off, [by_method[m]["mean_latency"] for m in methods], width, label=s["label"])
    first = {r["x"]: r for r in rows if r["sweep"] == sweep["name"]}
    axes[2].bar(pos, [first[m]["bits_per_ray"] for m in methods], 0.6, color="C2")
    axes[2].set_ylim(250, max(first[m]["bits_per_ray"] for m in methods) + 10)
    axes[0].set_yscale("log")
    axes[0].set_ylabel("cycles per ray\n(total cycles / rays)")
    axes[1].set_ylabel("mean ray latency\n(cycles)")
    axes[2].set_ylabel("bits per ray in flight")
    for ax in axes:
        ax.grid(True, axis="y", linewidth=0.4, alpha=0.5)
    axes[0].legend(fontsize=7)
    axes[0].set_title(sweep["title"], fontsize=9)
    axes[2].set_xticks(pos)
    axes[2].set_xticklabels(methods, rotation=40, ha="right", fontsize=7)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


CHARTS = {"scaling": plot_lines, "lines": plot_lines, "cache": plot_cache, "stalls": plot_stalls,
          "methods": plot_methods}
