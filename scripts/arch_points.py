"""Sweep points of the cycle-level model (used by arch_sweep.py).

A point is one `vbsim replay TRACE --mode cycle --config POINT.json --stats OUT.json`
process: a trace, a configuration (an `hw` object and nothing else) and a method
written in `vbsim score`'s syntax, `METHOD[+METHOD][:KEY=VALUE...]` with KEY a
`vbsim replay` option without its dashes. Points run through point_jobs.py
(local processes or a Slurm job array); finished points are kept in a cache
folder under a key made of the vbsim binary's contents, the trace's contents, the
configuration and the method, so a rerun skips every point it has already done
with the same build (a rebuilt model reruns them all).
"""
import json
import os
import sys

from point_jobs import Point, content_key, file_digest, write_json_once

MEMORY_STALLS = ("l1_mshr_full", "l2_mshr_full", "dram_outstanding_full", "dram_bandwidth")
STALL_CAUSES = ("memory_wait", "box_pipeline_full", "triangle_pipeline_full",
                "avoidance_pipeline_full", "stack_refill_wait")

def method_args(spec):
    """`vbsim replay` options of a method spec: `validity-bit:vb-policy=vote` ->
    ['--method', 'validity-bit', '--vb-policy', 'vote']. vb-tests joins its tests
    with '+' in a spec and with ',' on the command line."""
    name, *options = spec.split(":")
    args = ["--method", name]
    for option in options:
        key, eq, value = option.partition("=")
        if not eq or not key:
            sys.exit(f"arch_sweep: method '{spec}': '{option}' is not KEY=VALUE")
        args += [f"--{key}", value.replace("+", ",") if key == "vb-tests" else value]
    return args


def trace_digest(path):
    """SHA-256 of a file's bytes, a trace's or the vbsim binary's (computed once per run)."""
    return file_digest(path)


def point_key(vbsim, trace, config, method):
    return content_key(vbsim=trace_digest(vbsim), trace=trace_digest(trace), config=config, method=method)


def arch_point(vbsim, cache, trace, config, method):
    """The point of one cycle-level replay; writes its configuration file into the cache."""
    key = point_key(vbsim, trace, config, method)
    os.makedirs(cache, exist_ok=True)
    config_path = os.path.join(cache, key + ".config.json")
    write_json_once(config_path, config, indent=1, sort_keys=True)
    result = os.path.join(cache, key + ".stats.json")
    command = [vbsim, "replay", trace, "--mode", "cycle", "--config", config_path,
               "--stats", result + ".part", "-q", *method_args(method)]
    return Point(f"{os.path.basename(trace)} {method} {json.dumps(config, sort_keys=True)}", [command], result)


def bound_terms(stats):
    """The throughput bound of docs/hw-model.md, term by term, in rays per cycle:
    the source (its lanes over their busy cycles per ray) and each unit kind (cores x count /
    (issue interval x operations per ray)). A unit kind with no operation sets no bound."""
    hw, cfg = stats["hw"], stats["config"]["hw"]
    rays = hw["rays"] or 1
    lanes = cfg.get("source", {}).get("rays_per_cycle", 1)
    terms = {"source": lanes * rays / max(hw["source"]["busy_cycles"], 1)}
    for unit in ("box", "triangle", "avoidance"):
        ops_per_ray = hw["units"][unit]["ops_per_ray"]
        if ops_per_ray > 0:
            u = cfg[unit]
            terms[unit] = cfg["cores"] * u["count"] / (u["issue_interval"] * ops_per_ray)
    return terms


def summarise(stats):
    """The figures a chart or table needs, flat."""
    hw = stats["hw"]
    cfg = stats["config"]["hw"]
    port = hw["memory"].get("port", {})
    terms = bound_terms(stats)
    rays = hw["rays"]
    return {
        "rays": rays,
        "cycles": hw["cycles"],
        "rays_per_cycle": hw["rays_per_cycle"],
        "rays_per_s": hw["rays_per_s"],
        "clock_mhz": hw["clock_mhz"],
        "cycles_per_ray": hw["cycles"] / rays if rays else 0.0,
        "mean_latency": hw["latency"]["mean"],
        "box_ops_per_ray": hw["units"]["box"]["ops_per_ray"],
        "triangle_ops_per_ray": hw["units"]["triangle"]["ops_per_ray"],
        "avoidance_ops_per_ray": hw["units"]["avoidance"]["ops_per_ray"],
        "box_ops_per_s": hw["units"]["box"]["ops"] / hw["cycles"] * hw["clock_mhz"] * 1e6 if hw["cycles"] else 0.0,
        "utilisation": dict(hw["utilisation"]),
        "stall_shares": {c: hw["stalls"]["share_of_slot_cycles"][c] for c in STALL_CAUSES},
        "no_free_slot_cycles": hw["stalls"]["no_free_slot_cycles"],
        "l1_hit_rate": port.get("l1", {}).get("hit_rate"),
        "l2_hit_rate": port.get("l2", {}).get("hit_rate"),
        "dram_bandwidth_use": port.get("dram", {}).get("bandwidth_use"),
        # Memory-side waits (docs/memory-model.md) per line request; none with the ideal memory.
        "memory_stalls_per_line": {c: port["stall_cycles"][c] / max(port["line_requests"], 1)
                                   for c in MEMORY_STALLS} if "stall_cycles" in port else {},
        "bits_per_ray": stats["config"]["bits_per_ray"],
        "bound_terms": terms,
        "bound": min(terms.values()),
        "cores": cfg["cores"],
        "slots_per_core": cfg["slots_per_core"],
        "ideal_memory": cfg["memory"]["ideal"],
        "dependencies": cfg.get("source", {}).get("dependencies", False),
        "lane_idle_for_parents": hw.get("emission", {}).get("share_of_lane_cycles", {}).get("idle_for_dependencies"),
    }


def merge(base, override):
    """A copy of nested dict `base` with `override`'s fields replacing its own."""
    out = dict(base)
    for k, v in override.items():
        out[k] = merge(out[k], v) if isinstance(v, dict) and isinstance(out.get(k), dict) else v
    return out


def set_path(d, dotted, value):
    """A copy of nested dict `d` with the field at 'a.b.c' set to `value`."""
    head, _, rest = dotted.partition(".")
    out = dict(d)
    out[head] = set_path(out.get(head, {}), rest, value) if rest else value
    return out
