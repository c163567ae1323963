"""Methods' cost in cycles on every scenario family (used by arch_sweep.py).

Each registered scenario is generated small (`vbsim gen SCENARIO --rays N --seed K`)
into its own folder, a family named after the folder, as `vbsim score` names it;
bundled traces are families named after their folder too. Traces of different
scenes cannot be concatenated, so a family with many traces (random-triangles
writes one per triangle) is measured on a bounded, evenly spaced sample of them.
Each (family, method) is replayed twice per trace: on one core with one ray slot
(the per-ray cost without overlap) and on the preset (the throughput cost; short
traces include the pipeline's fill and drain). Cycles and rays are summed over the
sampled traces; latencies are ray-weighted means.
"""
import glob
import os

from arch_points import merge

SERIAL = {"cores": 1, "slots_per_core": 1}


def generate_family(run, vbsim, work, scenario, rays, seed):
    """The family folder of a scenario, generated once per (rays, seed)."""
    out = os.path.join(work, "families", scenario)
    marker = os.path.join(out, ".complete")
    cmd = [vbsim, "gen", scenario, "--rays", str(rays), "--seed", str(seed), "-o", out]
    if not (os.path.exists(marker) and open(marker).read() == " ".join(cmd[1:])):
        run(cmd)
        with open(marker, "w") as f:
            f.write(" ".join(cmd[1:]))
    return out


def sample(traces, most):
    """At most `most` traces, evenly spaced over the sorted list, both ends included."""
    if len(traces) <= most:
        return traces
    if most == 1:
        return traces[:1]
    return [traces[round(i * (len(traces) - 1) / (most - 1))] for i in range(most)]


def family_traces(run, vbsim, work, spec, scenarios, root, folders=None):
    """[(family name, sampled traces, number of traces in the family)]: the
    given family folders (as `vbsim score` scored them), or else each scenario
    generated small."""
    if not folders:
        folders = [generate_family(run, vbsim, work, s, spec["rays"], spec["seed"]) for s in scenarios]
    families = []
    for folder in folders:
        traces = sorted(glob.glob(os.path.join(folder, "*.jsonl")))
        families.append((os.path.basename(folder), sample(traces, spec["max_traces"]), len(traces)))
    for path in spec.get("bundled", []):
        full = os.path.join(root, path)
        families.append((os.path.basename(os.path.dirname(full)), [full], 1))
    return families


def family_points(families, spec):
    """Points (trace, config, method) and, in the same order, (family, method, run kind)."""
    preset = spec.get("preset", "small")
    runs = {"serial": {"hw": merge({"preset": preset}, SERIAL)}, "preset": {"hw": {"preset": preset}}}
    points, labels = [], []
    for family, traces, _ in families:
        for method in spec["methods"]:
            for kind, config in runs.items():
                for trace in traces:
                    points.append((trace, config, method))
                    labels.append((family, method, kind))
    return points, labels


def family_rows(families, spec, labels, summaries):
    """The rows of method_cycles.json: one per (family, method)."""
    totals = {}
    for (family, method, kind), s in zip(labels, summaries):
        t = totals.setdefault((family, method, kind), {"rays": 0, "cycles": 0, "latency_sum": 0.0, "bits": 0})
        t["rays"] += s["rays"]
        t["cycles"] += s["cycles"]
        t["latency_sum"] += s["mean_latency"] * s["rays"]
        t["bits"] = s["bits_per_ray"]

    def figures(t):
        n = t["rays"]
        return {"rays": n, "cycles": t["cycles"], "cycles_per_ray": t["cycles"] / n if n else 0.0,
                "mean_latency": t["latency_sum"] / n if n else 0.0}

    rows = []
    for family, traces, total in families:
        for method in spec["methods"]:
            thr, ser = totals[(family, method, "preset")], totals[(family, method, "serial")]
            rows.append({"family": family, "method": method, **figures(thr),
                         "bits_per_ray": thr["bits"], "traces": len(traces), "traces_in_family": total,
                         "one_core_one_slot": figures(ser)})
    return rows
