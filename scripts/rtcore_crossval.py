#!/usr/bin/python3
"""Cross-validation of vbsim's timing against rtcore-systemc, regime by regime.

    /usr/bin/python3 scripts/rtcore_crossval.py [--rtcore-src DIR] [--rays N] [--scene OBJ]
        [--vbsim PATH] [--work DIR] [--out FILE]

Both simulators run the same primary rays over the same mesh (`vbsim gen paths` camera
rays, written for rtcore by `vbsim convert --to rtcore --scene-out`), in each of the
regimes below: rtcore-systemc with its `tb_top` arguments, vbsim with the configuration
scripts/rtcore_config.py gives for the same arguments. The page (default
docs/results/rtcore-crossval.md) has both cycle counts per ray, the per-ray latency
correlation, the work each side did (box and triangle operations, L1 misses) and each
side's busiest unit, which is what explains a residual.

rtcore-systemc is a peer, never part of vbsim: its source (a checkout with its
submodules bvh and happly; it needs libmpfr-dev) is given by --rtcore-src or
VBSIM_RTCORE_SRC, and built here with CMake into the work directory. Without it the
script says so and exits 0 without writing anything.

rtcore stops its simulation once the last ray is sent, leaving up to 32 rays unfinished.
Rays padded behind the real ones would change the tail (each costs rtcore a root-node
test in its high-precision box pool), so the run is measured before that tail instead:
cycles per ray on both sides are the cycle at which all but the last TAIL_RAYS rays
(64) have finished, over their number. Per-ray latency (rtcore: the cycle a ray is
accepted to its result; vbsim: the cycle it starts in a slot to its finish, --ray-log)
is compared over the rays rtcore finished.

vbsim runs each regime twice: over its default tree (Embree's, leaves of up to 4
triangles) and over a tree of rtcore's kind (TREES: vbsim's own sweep-SAH builder with
leaves of up to 16, as rtcore's builder makes them), so the page tells the tree's part
of each residual from the timing's.
"""
import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import rtcore_config  # noqa: E402

TAIL_RAYS = 64
# rtcore tb_top arguments: LP_L1C HP_L1C IST_L1C T_TRAV_HIGH T_TRAV_LOW NUM_LP NUM_HP NUM_IST.
REGIMES = [
    ("rtcore's defaults: one triangle unit", "triangle-unit-bound", [512, 512, 512, 0.5, 0.47, 4, 4, 1]),
    ("two triangle units", "triangle-unit-bound", [512, 512, 512, 0.5, 0.47, 4, 4, 2]),
    ("one box unit per pool, four triangle units", "box-unit-bound", [512, 512, 512, 0.5, 0.47, 1, 1, 4]),
    ("one unit of each kind", "one unit", [512, 512, 512, 0.5, 0.47, 1, 1, 1]),
    ("32 units of each kind", "many units: controller-bound", [512, 512, 512, 0.5, 0.47, 32, 32, 32]),
    ("64-entry caches, 32 units", "cache-bound", [64, 64, 64, 0.5, 0.47, 32, 32, 32]),
    ("16-entry caches, 32 units", "cache-bound", [16, 16, 16, 0.5, 0.47, 32, 32, 32]),
    ("2-entry caches, 32 units", "memory-bound", [2, 2, 2, 0.5, 0.47, 32, 32, 32]),
    ("16-entry caches, one triangle unit", "cache and unit", [16, 16, 16, 0.5, 0.47, 4, 4, 1]),
]
# vbsim's trees: the key of its figures in a row, the options, and how the page names it.
TREES = [
    ("embree", [], "Embree's with at most 4 triangles a leaf"),
    ("sweep", ["--bvh-builder", "sweep-sah", "--bvh-leaf-size", "16"],
     "its own sweep SAH with at most 16 triangles a leaf, as rtcore builds its tree"),
]
SENT = re.compile(r"m_shader @ (\d+),\w+: ray sent, id=(\d+) \(count=(\d+)\)")
RESULT = re.compile(r"m_shader @ (\d+),\w+: result received, id=(\d+)")
COUNT = re.compile(r"^(m_rtcore\.\S+):\s*$")


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        sys.exit(f"rtcore_crossval.py: {' '.join(map(str, cmd))} failed ({r.returncode}):\n{r.stderr[-2000:]}")
    return r


def build_rtcore(src, work):
    build = os.path.join(work, "rtcore-build")
    tb_top = os.path.join(build, "tb_top")
    if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
        run(["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release"])
    run(["cmake", "--build", build, "--target", "tb_top", "-j", str(os.cpu_count() or 1)])
    return tb_top


def make_rays(vbsim, scene, rays, work):
    """Primary rays of `rays` camera paths over `scene`: vbsim's trace and rtcore's ray and mesh files."""
    gen = os.path.join(work, "gen")
    run([vbsim, "gen", "paths", "--rays", str(rays), "--seed", "1", "--set", f"scene={scene}", "-q", "-o", gen])
    with open(os.path.join(gen, "paths.jsonl")) as f:
        header, *lines = f.read().splitlines()
    head = json.loads(header)
    head["scene"] = os.path.normpath(os.path.join(gen, head["scene"])) if not os.path.isabs(head["scene"]) \
        else head["scene"]
    primary = [l for l in lines if json.loads(l).get("parent", -1) == -1]
    trace = os.path.join(work, "primary.jsonl")
    with open(trace, "w") as f:
        f.write(json.dumps(head) + "\n" + "\n".join(primary) + "\n")
    ray_file, mesh = os.path.join(work, "rays.bin"), os.path.join(work, "mesh.ply")
    run([vbsim, "convert", trace, "--to", "rtcore", "-o", ray_file, "--scene-out", mesh, "-q"])
    return trace, ray_file, mesh, len(primary)


def measured_cycle(finishes, n):
    """The cycle by which all but the last TAIL_RAYS of `n` rays had finished."""
    k = n - TAIL_RAYS
    if len(finishes) < k:
        sys.exit(f"rtcore_crossval.py: only {len(finishes)} of {n} rays finished")
    return sorted(finishes)[k - 1]


def run_rtcore(tb_top, mesh, ray_file, args, n):
    """The measured cycle, per-ray latencies (None: not finished), and the counts rtcore prints."""
    r = run([tb_top, mesh, ray_file, *map(str, args)], cwd=os.path.dirname(tb_top))
    slot_ray, sent, latency, finishes = {}, {}, [None] * n, []
    counts, module = {}, None
    for line in r.stdout.splitlines():
        if m := SENT.match(line):
            t, slot, count = map(int, m.groups())
            slot_ray[slot] = count - 1
            sent[count - 1] = t
        elif m := RESULT.match(line):
            t, slot = map(int, m.groups())
            ray = slot_ray.pop(slot)
            latency[ray] = t - sent[ray]
            finishes.append(t)
        elif m := COUNT.match(line):
            module = m.group(1)
        elif module and (m := re.match(r"^(miss|hit) = (\d+)$", line)):
            counts[f"{module}.{m.group(1)}"] = int(m.group(2))
        elif m := re.match(r"^(lp|hp) processed (\d+) nodes$", line):
            counts[m.group(1)] = int(m.group(2))
        elif m := re.match(r"^ist processed (\d+) triangles$", line):
            counts["ist"] = int(m.group(1))
    if len(sent) != n:
        sys.exit(f"rtcore_crossval.py: rtcore sent {len(sent)} of {n} rays")
    return {"cycles": measured_cycle(finishes, n), "end": max(finishes), "latency": latency, "counts": counts}


def run_vbsim(vbsim, trace, args, work, n, tree_options=()):
    cfg = os.path.join(work, "vbsim-config.json")
    with open(cfg, "w") as f:
        json.dump(rtcore_config.config(rtcore_config.parse(list(map(str, args)))), f)
    stats, log = os.path.join(work, "vbsim-stats.json"), os.path.join(work, "vbsim-rays.jsonl")
    run([vbsim, "replay", trace, "--mode", "cycle", "--config", cfg, "-m", "none", "--deps", "off",
         "--stats", stats, "--ray-log", log, "-q", *tree_options])
    with open(stats) as f:
        hw = json.load(f)["hw"]
    with open(log) as f:
        rows = [json.loads(l) for l in f]
    if len(rows) != n:
        sys.exit(f"rtcore_crossval.py: vbsim's ray log has {len(rows)} rays, the trace {n}")
    return {"cycles": measured_cycle([r["finish"] for r in rows], n), "latency": [r["finish"] - r["start"] for r in rows],
            "hw": hw}


def pearson(a, b):
    return statistics.correlation(a, b) if len(a) > 2 and len(set(a)) > 1 and len(set(b)) > 1 else float("nan")


def busiest_rtcore(args, c, cycles):
    """Each rtcore unit pool's busy fraction: operations x latency / (units x cycles)."""
    lp, hp, ist = args[5], args[6], args[7]
    return {"box (lp)": c.get("lp", 0) * 20 / (lp * cycles), "box (hp)": c.get("hp", 0) * 20 / (hp * cycles),
            "triangle": c.get("ist", 0) * 32 / (ist * cycles)}


def row(name, bound, args, rt, vb, n):
    c, hw = rt["counts"], vb["hw"]
    k = n - TAIL_RAYS
    rt_cpr, vb_cpr = rt["cycles"] / k, vb["cycles"] / k
    both = [i for i in range(n) if rt["latency"][i] is not None]
    rt_lat, vb_lat = [rt["latency"][i] for i in both], [vb["latency"][i] for i in both]
    rt_nodes = c.get("lp", 0) + c.get("hp", 0)
    rt_misses = sum(v for k, v in c.items() if k.endswith(".miss"))
    rt_busy = busiest_rtcore(args, c, rt["end"])
    # vbsim's pools by rtcore's names: its full-precision box unit (hp), its low-precision pool (lp).
    vb_busy = {"box (hp)": hw["utilisation"]["box"], "box (lp)": hw["utilisation"].get("box_low", 0.0),
               "triangle": hw["utilisation"]["triangle"]}
    vb_high = hw["units"]["box"]["ops"]
    vb_low = hw["units"]["box_low"]["ops"] if "box_low" in hw["units"] else 0
    port = hw["memory"]["port"]
    return {
        "regime": name, "bound": bound, "args": " ".join(map(str, args)), "rays": n,
        "rtcore_cycles_per_ray": rt_cpr, "vbsim_cycles_per_ray": vb_cpr,
        "difference": vb_cpr / rt_cpr - 1, "latency_correlation": pearson(rt_lat, vb_lat),
        "rtcore_mean_latency": statistics.fmean(rt_lat), "vbsim_mean_latency": statistics.fmean(vb_lat),
        "rtcore_nodes_per_ray": rt_nodes / n, "vbsim_box_ops_per_ray": (vb_high + vb_low) / n,
        "vbsim_lp_per_ray": vb_low / n, "vbsim_hp_per_ray": vb_high / n,
        "rtcore_triangles_per_ray": c.get("ist", 0) / n, "vbsim_triangles_per_ray": hw["units"]["triangle"]["ops"] / n,
        "rtcore_l1_misses": rt_misses, "vbsim_l1_misses": port["l1"]["misses"], "vbsim_dram_reads": port["dram"]["reads"],
        "rtcore_l1_misses_per_ray": rt_misses / n, "vbsim_l1_misses_per_ray": port["l1"]["misses"] / n,
        "rtcore_lp_per_ray": c.get("lp", 0) / n, "rtcore_hp_per_ray": c.get("hp", 0) / n,
        # rtcore's misses by cache: low-precision nodes, other nodes, triangles.
        "rtcore_misses_by_cache": {cache: sum(v for k, v in c.items() if k.endswith(".miss") and cache in k)
                                   for cache in ("l1c_lp", "l1c_hp", "ist_l1c")},
        # vbsim's by its object caches (memory.objects), in rtcore's order.
        "vbsim_misses_by_cache": {rt: port["objects"][vb]["misses"] for rt, vb in
                                  (("l1c_lp", "node_low"), ("l1c_hp", "node"), ("ist_l1c", "triangle"))}
        if "objects" in port else None,
        "vbsim_dram_bytes": port["dram"].get("bytes", 0),
        "rtcore_busy": rt_busy, "vbsim_busy": vb_busy,
    }


def controller_text():
    """The rtcore preset's controller, in words."""
    with open(os.path.join(ROOT, "model", "hw", "presets", "rtcore.json")) as f:
        c = json.load(f)["controller"]
    by = {k: v for k, v in c.get("by_step", {}).items()}
    take = ", ".join(f"a {k} step's end {v.get('issue_interval', c['issue_interval'])}" for k, v in by.items())
    return (f"one controller taking a step's end every {c['issue_interval']} cycle(s)"
            + (f" ({take})" if take else "") + f" and {c['latency']} cycles of hops a step")


CONTROLLER_TEXT = controller_text()


def explain(r, tree):
    """What the measured counts say about the residual, vbsim running over `tree` (TREES' name)."""
    lp_units, hp_units = (int(x) for x in r["args"].split()[5:7])
    rt_unit, rt_b = max(r["rtcore_busy"].items(), key=lambda kv: kv[1])
    vb_unit, vb_b = max(r["vbsim_busy"].items(), key=lambda kv: kv[1])
    tri = r["vbsim_triangles_per_ray"] / r["rtcore_triangles_per_ray"] - 1
    box = r["vbsim_box_ops_per_ray"] / r["rtcore_nodes_per_ray"] - 1
    parts = [f"busiest units: rtcore's {rt_unit} {rt_b:.0%}, vbsim's {vb_unit} {vb_b:.0%}"]
    if rt_unit == vb_unit == "triangle" and min(rt_b, vb_b) >= 0.9:
        parts.append(f"both bound by the triangle units, so the cycles follow the triangle tests: vbsim's tree "
                     f"needs {tri:+.1%} a ray, the cycles differ by {r['difference']:+.1%}")
    elif vb_unit.startswith("box") and rt_unit.startswith("box") and min(rt_b, vb_b) >= 0.9:
        pool = "lp" if vb_unit == "box (lp)" else "hp"
        units = lp_units if pool == "lp" else hp_units
        rt_pool, vb_pool = r[f"rtcore_{pool}_per_ray"], r[f"vbsim_{pool}_per_ray"]
        predicted = vb_pool / rt_pool - 1 if rt_pool else float("nan")
        parts.append(f"both bound by box units: vbsim's busiest pool ({pool}, {units} units) tests "
                     f"{vb_pool:.2f} nodes a ray, rtcore's {rt_pool:.2f} (the other pool: vbsim "
                     f"{r['vbsim_box_ops_per_ray'] - vb_pool:.2f}, rtcore {r['rtcore_nodes_per_ray'] - rt_pool:.2f}); "
                     f"that pool's work alone predicts {predicted:+.1%}, measured {r['difference']:+.1%}")
    elif r["rtcore_l1_misses_per_ray"] > 1:
        m = r["rtcore_misses_by_cache"]
        # rtcore's objects (bbox_ctrl, ist_ctrl): a node whose two children are low precision 40 bytes, another
        # 52 or 64, a triangle 36; a miss is a DRAM read of 5 cycles a byte.
        low = (m["l1c_lp"] * 40 + m["l1c_hp"] * 52 + m["ist_l1c"] * 36) * 5 / r["rays"]
        high = (m["l1c_lp"] * 40 + m["l1c_hp"] * 64 + m["ist_l1c"] * 36) * 5 / r["rays"]
        v = r["vbsim_misses_by_cache"]
        vb = (r["vbsim_dram_bytes"] * 5 + r["vbsim_l1_misses_per_ray"] * r["rays"]) / r["rays"]
        per = lambda d: ", ".join(f"{d[k] / r['rays']:.2f}" for k in ("l1c_lp", "l1c_hp", "ist_l1c"))
        parts.append(f"memory-bound: both miss objects of three caches (low-precision nodes of 40 bytes, other "
                     f"nodes of 52 or 64 in rtcore and 64 in vbsim, triangles of 36), each a DRAM read of 5 cycles "
                     f"a byte; misses a ray by cache, rtcore {per(m)}, vbsim {per(v) if v else 'n/a'} "
                     f"({r['vbsim_l1_misses_per_ray'] / r['rtcore_l1_misses_per_ray'] - 1:+.1%} in all); "
                     f"their DRAM cycles a ray, vbsim {vb:.0f}, rtcore {low:.0f} to {high:.0f} "
                     f"({vb / high - 1:+.1%} to {vb / low - 1:+.1%})")
    else:
        rt_steps = r["rtcore_nodes_per_ray"] + r["rtcore_triangles_per_ray"]
        vb_steps = r["vbsim_box_ops_per_ray"] + r["vbsim_triangles_per_ray"]
        rt_step, vb_step = r["rtcore_mean_latency"] / rt_steps, r["vbsim_mean_latency"] / vb_steps
        parts.append(f"no unit saturated: each ray's time in its slot bounds both (32 slots); a ray spends "
                     f"{r['rtcore_mean_latency']:.0f} cycles in a slot in rtcore, {r['vbsim_mean_latency']:.0f} in "
                     f"vbsim, over {rt_steps:.2f} and {vb_steps:.2f} node and triangle steps: the steps alone "
                     f"predict {vb_steps / rt_steps - 1:+.1%}, the time a step ({vb_step:.1f} cycles in vbsim, "
                     f"{rt_step:.1f} in rtcore) {vb_step / rt_step - 1:+.1%}; the step's time is the units' latency "
                     f"and the hops through rtcore's traversal and box or intersection controllers, arbiter, "
                     f"FIFOs and caches, which the preset gives as {CONTROLLER_TEXT}")
    parts.append(f"(vbsim's tree, {tree}, needs {box:+.1%} node tests and "
                 f"{tri:+.1%} triangle tests a ray against rtcore's sweep-SAH tree)")
    return "; ".join(parts)


def page(rows, n, scene, rays_file):
    out = ["# Timing cross-validated against rtcore-systemc", "",
           "Regenerated by `scripts/rtcore_crossval.py` (it builds rtcore-systemc from a source",
           "checkout given by `--rtcore-src` or `VBSIM_RTCORE_SRC`, and is skipped without one). "
           f"{n:,} primary rays of `vbsim gen paths --rays {n} --seed 1` over `{os.path.relpath(scene, ROOT)}`; "
           "vbsim runs the configuration "
           "`scripts/rtcore_config.py ARGS` prints (the `rtcore` preset, `docs/hw-model.md`, "
           "\"Modelling rtcore-systemc\"), method `none`, every ray independent.", "",
           f"rtcore stops once its last ray is sent, so cycles per ray are, on both sides, the cycle by which all "
           f"but the last {TAIL_RAYS} rays had finished over their number; latency is a ray's cycles from entering "
           "a slot to its result, and its correlation the Pearson coefficient over the rays rtcore finished. "
           "Node and triangle tests and misses are whole-run counts.", ""]
    header = ["| regime | rtcore arguments | rtcore cycles/ray | vbsim cycles/ray | difference | latency correlation | "
              "node tests/ray rtcore, vbsim | low-precision share rtcore, vbsim | "
              "triangle tests/ray rtcore, vbsim | L1 misses rtcore, vbsim |",
              "|---|---|---|---|---|---|---|---|---|---|"]

    def table(key):
        lines = []
        for row in rows:
            r = row[key]
            lines.append(f"| {r['regime']} ({r['bound']}) | `{r['args']}` | {r['rtcore_cycles_per_ray']:.2f} | "
                         f"{r['vbsim_cycles_per_ray']:.2f} | {r['difference']:+.1%} | "
                         f"{r['latency_correlation']:.3f} | "
                         f"{r['rtcore_nodes_per_ray']:.2f}, {r['vbsim_box_ops_per_ray']:.2f} | "
                         f"{r['rtcore_lp_per_ray'] / r['rtcore_nodes_per_ray']:.0%}, "
                         f"{r['vbsim_lp_per_ray'] / r['vbsim_box_ops_per_ray']:.0%} | "
                         f"{r['rtcore_triangles_per_ray']:.2f}, {r['vbsim_triangles_per_ray']:.2f} | "
                         f"{r['rtcore_l1_misses']:,}, {r['vbsim_l1_misses']:,} |")
        within = sum(abs(row[key]["difference"]) <= 0.05 for row in rows)
        return lines + ["", f"Within 5%: {within} of {len(rows)} regimes."]

    (first, _, first_tree), (second, second_options, second_tree) = TREES
    out += [f"vbsim over its default tree ({first_tree}):", "", *header, *table(first), "",
            f"vbsim over a tree of rtcore's kind ({second_tree}: `{' '.join(second_options)}`):", "",
            *header, *table(second), "",
            "| regime | difference, vbsim's default tree | difference, sweep SAH (16) | residual's size, change |",
            "|---|---|---|---|"]
    for row in rows:
        a, b = row[first]["difference"], row[second]["difference"]
        out.append(f"| {row[first]['regime']} | {a:+.1%} | {b:+.1%} | {100 * (abs(b) - abs(a)):+.1f} points |")
    out += ["", "## What explains each residual", ""]
    for row in rows:
        r, q = row[first], row[second]
        out.append(f"- **{r['regime']}** ({r['difference']:+.1%}; {q['difference']:+.1%} over the sweep-SAH tree): "
                   f"{explain(r, first_tree)}. Over the sweep-SAH tree: {explain(q, second_tree)}.")
    out += ["", "rtcore's node tests count each pool's operations (a node's two boxes each); vbsim's count its two "
            "pools' operations (two boxes each; the `rtcore` preset, as rtcore, fetches the root node first and "
            "tests no root box at dispatch, visits a popped subtree beyond the hit all the same and reads a leaf's "
            "triangles one by one). Both mark nodes low or high precision by rtcore's cost model (vbsim's "
            "implementation, `scene/bvh_precision.h`); the low-precision share is the part of the node tests the "
            "low-precision pool did. rtcore's L1 misses are its three "
            "object caches' (a bounding box, node record or triangle each); vbsim's are 64-byte lines of its one L1.",
            "", "vbsim's sweep-SAH builder splits as rtcore's builder does (a full sweep over the triangles' "
            "centroids, traversal cost 1, a median split past the largest leaf), so the node and triangle tests "
            "that still differ over its tree are the two traversals' rather than the trees'; the difference "
            "between the two tables is what the tree alone changes.", ""]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rtcore-src", default=os.environ.get("VBSIM_RTCORE_SRC"))
    ap.add_argument("--rays", type=int, default=16384)
    ap.add_argument("--scene", default=os.path.join(ROOT, "traces", "wuson", "WusonOBJ.obj"))
    ap.add_argument("--vbsim", default=os.path.join(ROOT, "build", "vbsim"))
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "rtcore-crossval"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "results", "rtcore-crossval.md"))
    a = ap.parse_args()
    src = a.rtcore_src
    if not src or not os.path.exists(os.path.join(src, "testbench", "tb_top.cpp")):
        print("rtcore_crossval.py: skipped: no rtcore-systemc source (give --rtcore-src DIR or VBSIM_RTCORE_SRC: "
              "a checkout of github lashhw/rtcore-systemc with its submodules, and libmpfr-dev installed)")
        return 0
    if not os.path.exists(os.path.join(src, "src", "third_party", "bvh", "CMakeLists.txt")):
        sys.exit(f"rtcore_crossval.py: {src} has no src/third_party/bvh: check out its submodules")
    os.makedirs(a.work, exist_ok=True)
    tb_top = build_rtcore(os.path.abspath(src), a.work)
    trace, ray_file, mesh, n = make_rays(a.vbsim, os.path.abspath(a.scene), a.rays, a.work)
    rows = []
    for name, bound, args in REGIMES:
        rt = run_rtcore(tb_top, mesh, ray_file, args, n)
        rows.append({})
        for key, tree_options, _ in TREES:
            vb = run_vbsim(a.vbsim, trace, args, a.work, n, tree_options)
            r = rows[-1][key] = row(name, bound, args, rt, vb, n)
            print(f"{name} ({key}): rtcore {r['rtcore_cycles_per_ray']:.2f}, vbsim {r['vbsim_cycles_per_ray']:.2f} "
                  f"cycles/ray ({r['difference']:+.1%}), latency correlation {r['latency_correlation']:.3f}",
                  flush=True)
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        f.write(page(rows, n, a.scene, ray_file))
    os.replace(tmp, a.out)
    with open(os.path.join(a.work, "rows.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print(f"rtcore_crossval.py: wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
