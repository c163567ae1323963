#!/usr/bin/python3
"""How vbsim's own cost grows with the scene and with the rays.

Makes Wuson (traces/wuson) subdivided 1 to N times (scripts/subdivide_mesh.py:
every triangle split into four, so 14,928 to 15,286,272 triangles at N = 6),
then runs `vbsim bench` (random rays, one thread, functional and cycle-level on
the small preset) under /usr/bin/time -v on each, and on one scene at several
ray counts. Records per run: the BVH build time, vbsim's and Embree's rays/s
(timed in the same run), the whole command's wall time and peak resident set;
fits a power law (least squares on log-log) to each series; writes a markdown
page, a CSV and a chart.

  /usr/bin/python3 scripts/scaling.py --rounds 6 --rays 200000 \
      --ray-counts 250000,1000000,4000000 --page docs/results/scaling.md

Outputs are written to temporaries and renamed when complete.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np

import suite_measure as measure

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WUSON = os.path.join(ROOT, "traces", "wuson", "WusonOBJ.obj")


def subdivided(out_dir, rounds):
    """The path of Wuson subdivided `rounds` times, made once (each level from the one before)."""
    path = os.path.join(out_dir, f"wuson-sub{rounds}.obj")
    if not os.path.exists(path):
        source = WUSON if rounds == 1 else subdivided(out_dir, rounds - 1)
        tmp = path + ".part"
        subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "subdivide_mesh.py"), source, "1", "-o", tmp],
                       check=True, stdout=subprocess.DEVNULL)
        os.replace(tmp, path)
    return path


def timed_bench(vbsim, scene, rays, mode):
    """One `vbsim bench` run of random rays under /usr/bin/time -v: its figures, wall time and peak RSS."""
    with tempfile.TemporaryDirectory() as tmp:
        try:
            info, result = measure.bench_json(vbsim, ["--scene", scene, "--rays", str(rays)], mode, "none", 1,
                                              os.path.join(tmp, "b.json"), os.path.join(tmp, "b.log"))
        except measure.RunError as e:
            raise SystemExit(f"scaling: {e}")
    if info["peak_rss_kb"] is None:
        raise SystemExit(f"scaling: {measure.TIME} is missing (scripts/setup.sh installs it)")
    return {"mode": mode, "triangles": result["triangles"], "rays": result["rays"],
            "bvh_build_s": result["bvh_build_s"], "vbsim_rays_per_s": result["vbsim_rays_per_s"],
            "embree_rays_per_s": result["embree_rays_per_s"], "ratio": result["ratio"],
            "wall_s": info["wall_s"], "peak_rss_bytes": info["peak_rss_kb"] * 1024}


def exponent(xs, ys):
    """The b of y = a x^b fitted by least squares on logarithms, over every point and over the
    two largest x only (where fixed costs, such as the program's own 70 MB, weigh least)."""
    whole = float(np.polyfit(np.log(xs), np.log(ys), 1)[0])
    last = float(np.log(ys[-1] / ys[-2]) / np.log(xs[-1] / xs[-2])) if len(xs) >= 2 else float("nan")
    return whole, last


def write_atomically(path, text):
    tmp = path + ".part"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--vbsim", default=os.path.join(ROOT, "build", "vbsim"))
    ap.add_argument("--rounds", type=int, default=6, help="largest subdivision (1..7) [6: 15,286,272 triangles]")
    ap.add_argument("--rays", type=int, default=200000, help="random rays of each scene's runs")
    ap.add_argument("--ray-counts", default="250000,1000000,4000000", help="ray counts of the ray series")
    ap.add_argument("--ray-scene-rounds", type=int, default=4, help="the ray series' scene [4: 955,392 triangles]")
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "scaling"), help="scenes and raw results")
    ap.add_argument("--page", default=None, help="markdown page [OUT/scaling.md]; chart and CSV beside it")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    page = a.page or os.path.join(a.out, "scaling.md")
    ray_counts = [int(x) for x in a.ray_counts.split(",")]

    rows = []
    for rounds in range(1, a.rounds + 1):
        scene = subdivided(a.out, rounds)
        for mode in ("functional", "cycle"):
            r = timed_bench(a.vbsim, scene, a.rays, mode)
            r["series"] = "triangles"
            rows.append(r)
            print(f"scaling: {r['triangles']} triangles {mode}: {r['vbsim_rays_per_s']:.0f} rays/s, "
                  f"{r['peak_rss_bytes'] / 2**30:.2f} GiB", file=sys.stderr)
    ray_scene = subdivided(a.out, a.ray_scene_rounds)
    for rays in ray_counts:
        for mode in ("functional", "cycle"):
            r = timed_bench(a.vbsim, ray_scene, rays, mode)
            r["series"] = "rays"
            rows.append(r)
            print(f"scaling: {rays} rays {mode}: {r['wall_s']:.1f} s", file=sys.stderr)

    base = os.path.splitext(page)[0]
    fields = ["series", "mode", "triangles", "rays", "bvh_build_s", "vbsim_rays_per_s", "embree_rays_per_s",
              "ratio", "wall_s", "peak_rss_bytes"]
    with open(base + ".csv.part", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    os.replace(base + ".csv.part", base + ".csv")

    def series(name, mode):
        return [r for r in rows if r["series"] == name and r["mode"] == mode]

    fits = {}
    for mode in ("functional", "cycle"):
        t = series("triangles", mode)
        n = [r["triangles"] for r in t]
        fits[(mode, "build")] = exponent(n, [r["bvh_build_s"] for r in t])
        fits[(mode, "rss")] = exponent(n, [r["peak_rss_bytes"] for r in t])
        fits[(mode, "time per ray")] = exponent(n, [1 / r["vbsim_rays_per_s"] for r in t])
        fits[(mode, "embree time per ray")] = exponent(n, [1 / r["embree_rays_per_s"] for r in t])
        rr = series("rays", mode)
        if len(rr) >= 2:
            fits[(mode, "run time against rays")] = exponent([r["rays"] for r in rr],
                                                             [r["rays"] / r["vbsim_rays_per_s"] for r in rr])
            fits[(mode, "rss against rays")] = exponent([r["rays"] for r in rr], [r["peak_rss_bytes"] for r in rr])

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for mode, style in (("functional", "o-"), ("cycle", "s-")):
        t = series("triangles", mode)
        n = [r["triangles"] for r in t]
        ax[0].loglog(n, [1e6 / r["vbsim_rays_per_s"] for r in t], style, label=f"vbsim {mode}: us a ray")
        ax[0].loglog(n, [r["peak_rss_bytes"] / 2**20 for r in t], style, alpha=0.5, label=f"{mode}: peak MiB")
        rr = series("rays", mode)
        ax[1].loglog([r["rays"] for r in rr], [r["rays"] / r["vbsim_rays_per_s"] for r in rr], style,
                     label=f"vbsim {mode}: run s")
        ax[1].loglog([r["rays"] for r in rr], [r["peak_rss_bytes"] / 2**20 for r in rr], style, alpha=0.5,
                     label=f"{mode}: peak MiB")
    t = series("triangles", "functional")
    ax[0].loglog([r["triangles"] for r in t], [r["bvh_build_s"] for r in t], "^--", label="BVH build s")
    ax[0].loglog([r["triangles"] for r in t], [1e6 / r["embree_rays_per_s"] for r in t], "x:",
                 label="Embree: us a ray")
    ax[0].set_xlabel("triangles")
    ax[1].set_xlabel(f"rays ({series('rays', 'functional')[0]['triangles']:,} triangles)")
    for x in ax:
        x.grid(True, which="both", alpha=0.3)
        x.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(base + ".png.part.png", dpi=110)
    os.replace(base + ".png.part.png", base + ".png")

    lines = ["# Scaling: vbsim's cost against triangles and rays", "",
             "Written by `scripts/scaling.py` (" + " ".join(
                 f"`{x}`" for x in [f"--rounds {a.rounds}", f"--rays {a.rays}", f"--ray-counts {a.ray_counts}",
                                    f"--ray-scene-rounds {a.ray_scene_rounds}"]) + "). Each row is one "
             "`vbsim bench` command (random rays, one thread; cycle-level: the small preset) under "
             "`/usr/bin/time -v`: the wall time and peak resident set are the whole command's (loading, "
             "building, Embree's timing and vbsim's); rays/s are each side's best timed pass. The scenes are "
             "Wuson subdivided 1 to N times (`scripts/subdivide_mesh.py`).", "",
             "| series | mode | triangles | rays | BVH build s | vbsim rays/s | Embree rays/s | ratio | wall s "
             "| peak GiB |", "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['series']} | {r['mode']} | {r['triangles']:,} | {r['rays']:,} | {r['bvh_build_s']:.2f} "
                     f"| {r['vbsim_rays_per_s']:,.0f} | {r['embree_rays_per_s']:,.0f} | {r['ratio']:.3f} "
                     f"| {r['wall_s']:.1f} | {r['peak_rss_bytes'] / 2**30:.2f} |")
    lines += ["", "Fitted exponents b of y = a x^b (least squares on logarithms over every point, and between "
              "the two largest only; x the triangles, or the rays for the last two of each mode):", "",
              "| mode | quantity | b, every point | b, two largest |", "|---|---|---:|---:|"]
    for (mode, what), (b, last) in fits.items():
        lines.append(f"| {mode} | {what} | {b:.3f} | {last:.3f} |")
    rr = series("rays", "functional")
    if len(rr) >= 2:
        per_ray = (rr[-1]["peak_rss_bytes"] - rr[0]["peak_rss_bytes"]) / (rr[-1]["rays"] - rr[0]["rays"])
        lines += ["", f"The bench holds every ray it times in memory (its rays, both sides' answers): "
                  f"{per_ray:.0f} bytes a ray more peak between {rr[0]['rays']:,} and {rr[-1]['rays']:,} rays, "
                  "so a run of 100 M rays needs a trace and `vbsim replay`, which streams them."]
    lines += ["", f"![scaling]({os.path.basename(base)}.png)", ""]
    write_atomically(page, "\n".join(lines))
    print(f"scaling: wrote {page}", file=sys.stderr)


if __name__ == "__main__":
    main()
