"""The generated page docs/results/architecture.md (used by arch_sweep.py)."""
from arch_charts import STALL_LABELS
from arch_points import STALL_CAUSES
from provenance import provenance_comment

UNIT_TEXT = {"source": "ray-source", "box": "box-pipeline", "triangle": "triangle-pipeline",
             "avoidance": "avoidance-unit"}
PUBLISHED = {"rays_per_s": 300e6, "node_tests_per_s": 24e9, "clock_mhz": 600}


def limit_text(r):
    """What limits throughput at one point, from its bound terms and stalls."""
    terms = r["bound_terms"]
    unit = min(terms, key=terms.get)
    frac = r["rays_per_cycle"] / terms[unit]
    if frac >= 0.9:
        return f"{UNIT_TEXT[unit]} bound ({frac:.0%} of its {terms[unit]:.3g} rays/cycle)"
    cause = max(STALL_CAUSES, key=lambda c: r["stall_shares"][c])
    share = r["stall_shares"][cause]
    head = f"{frac:.0%} of the {UNIT_TEXT[unit]} bound; "
    slots = r["cores"] * r["slots_per_core"]
    if r["rays"] < 4 * slots:
        return head + f"a short run: {r['rays']} rays for {slots} slots, filling and draining dominate"
    if share >= 0.15:
        return head + f"{STALL_LABELS[cause]} takes {share:.0%} of slot-cycles" + memory_side(r)
    if r["utilisation"]["slots"] >= 0.8:
        return head + f"too few slots to hide a {r['mean_latency']:.0f}-cycle ray latency"
    return head + f"slots only {r['utilisation']['slots']:.0%} occupied (fill and drain of the run)"


def memory_side(r):
    """The main memory-side wait, when there is one worth naming (a cycle per line request)."""
    waits = r.get("memory_stalls_per_line") or {}
    if not waits:
        return ""
    cause = max(waits, key=waits.get)
    if waits[cause] < 1:
        return ""
    return f"; memory side: {cause.replace('_', ' ')}, {waits[cause]:.3g} cycles per line request"


def fmt(v, digits=3):
    if v is None:
        return "-"
    if isinstance(v, str):
        return v
    return f"{v:.{digits}g}" if isinstance(v, float) else str(v)


def x_text(sweep, x):
    """A sweep value in the unit of its axis (`xscale`), whole numbers without a point."""
    v = x / sweep.get("xscale", 1)
    return str(int(v)) if float(v).is_integer() else f"{v:g}"


def table(header, body):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(fmt(c) for c in row) + " |" for row in body]
    return lines


def sweep_section(group, sweeps, rows, image):
    """Chart, a table of rays per cycle (and the swept cache's hit rate), and the limits."""
    out = [f"## {group}", "", f"![{group}]({image})", ""]
    for sweep in sweeps:
        mine = [r for r in rows if r["sweep"] == sweep["name"]]
        labels = [s["label"] for s in sweep["series"]]
        header = [sweep["xlabel"]] + [f"rays/cycle: {label}" for label in labels]
        extra = sweep.get("hit_rate")
        if extra:
            header.append(extra.replace("_", " ") + f" ({labels[0]})")
        if any(s.get("bound") for s in sweep["series"]):
            header.append("analytic bound")
        body = []
        for x in sweep["values"]:
            at = {r["series"]: r for r in mine if r["x"] == x}
            row = [x_text(sweep, x)] + [at[label]["rays_per_cycle"] for label in labels]
            if extra:
                row.append(at[labels[0]][extra])
            bound = [s for s in sweep["series"] if s.get("bound")]
            if bound:
                row.append(at[bound[0]["label"]]["bound"])
            body.append(row)
        out += [f"**{sweep['title']}**", ""] + table(header, body) + [""]
        ends = (sweep["values"][0], sweep["values"][-1])
        limits = []
        for label in labels:
            at = {r["x"]: r for r in mine if r["series"] == label}
            limits.append(f"{label}: at {x_text(sweep, ends[0])}, {limit_text(at[ends[0]])}; "
                          f"at {x_text(sweep, ends[1])}, {limit_text(at[ends[1]])}")
        out += ["What limits throughput:", ""] + [f"- {text}." for text in limits]
        out.append("")
    return out


def methods_section(sweep, rows, image):
    out = [f"## {sweep['title']}", "", f"![methods]({image})", ""]
    labels = [s["label"] for s in sweep["series"]]
    header = ["method", "bits/ray"]
    for label in labels:
        header += [f"cycles/ray: {label}", f"mean latency: {label}"]
    header += ["avoidance ops/ray"]
    body = []
    for m in sweep["values"]:
        at = {r["series"]: r for r in rows if r["sweep"] == sweep["name"] and r["x"] == m}
        row = [f"`{m}`", at[labels[0]]["bits_per_ray"]]
        for label in labels:
            row += [at[label]["cycles_per_ray"], at[label]["mean_latency"]]
        row.append(at[labels[-1]]["avoidance_ops_per_ray"])
        body.append(row)
    out += table(header, body) + ["", "What limits throughput:", ""]
    for label in labels:
        mine = {r["x"]: r for r in rows if r["sweep"] == sweep["name"] and r["series"] == label}
        cheap = min(mine.values(), key=lambda r: r["cycles_per_ray"])
        dear = max(mine.values(), key=lambda r: r["cycles_per_ray"])
        out.append(f"- {label}: `{cheap['x']}` {cheap['cycles_per_ray']:.3g} cycles/ray, "
                   f"{limit_text(cheap)}; `{dear['x']}` {dear['cycles_per_ray']:.3g} cycles/ray, {limit_text(dear)}.")
    return out + [""]


def presets_section(preset_rows, method):
    out = ["## What the presets predict", "",
           f"Method `{method}`. One box operation tests both child boxes of a node, so child-box "
           "tests per second are twice the box operations. Published PowerVR figure for scale: "
           "300 Mrays/s and 24 G node tests/s at 600 MHz (40 node tests per cycle, 80 per ray).", ""]
    out += ["Dependencies `on`: a child ray waits for its parent's result plus the shading latency "
            "(`shader.latency_cycles`, docs/hw-model.md); `off`: every ray independent, as a trace of unrelated "
            "queries. Latency is from dispatch to result, per ray.", ""]
    header = ["preset", "trace", "memory", "dependencies", "rays", "cycles", "rays/cycle", "Mrays/s",
              "mean latency", "lanes idle for parents", "box ops/ray", "G box ops/s", "G child-box tests/s",
              "L1 hit", "L2 hit", "DRAM bandwidth use", "what limits it"]
    body = [[r["preset"], r["trace"], "ideal" if r["ideal_memory"] else "hierarchy",
             "on" if r.get("dependencies") else "off", r["rays"], r["cycles"], r["rays_per_cycle"],
             r["rays_per_s"] / 1e6, r["mean_latency"], r.get("lane_idle_for_parents"), r["box_ops_per_ray"],
             r["box_ops_per_s"] / 1e9, 2 * r["box_ops_per_s"] / 1e9, r["l1_hit_rate"], r["l2_hit_rate"],
             r["dram_bandwidth_use"], limit_text(r)]
            for r in preset_rows]
    return out + table(header, body) + [""]


def families_section(family_rows, spec, given_folders=None):
    families = list(dict.fromkeys(r["family"] for r in family_rows))
    sampled = [f"{r['family']} ({r['traces']} of {r['traces_in_family']})" for r in family_rows
               if r["method"] == family_rows[0]["method"] and r["traces"] < r["traces_in_family"]]
    if given_folders:
        made = "The families are the folders this run was given (`--families`), as `vbsim score` scored them"
    else:
        made = f"Each scenario generated with `vbsim gen SCENARIO --rays {spec['rays']} --seed {spec['seed']}`"
    bundled = [f"`{path}`" for path in spec.get("bundled", [])]
    if bundled:
        made += ", plus the bundled trace" + ("s " if len(bundled) > 1 else " ") + ", ".join(bundled) + \
            " (a family named after its folder)"
    out = ["## Methods' cost in cycles on every scenario family", "",
           made + f". At most {spec['max_traces']} traces per family, evenly spaced" +
           (f"; sampled: {', '.join(sampled)}" if sampled else "") + ". Full rows (rays, cycles, latency): "
           "`method_cycles.json` beside `arch_sweep.json`, joinable with `vbsim score` rows by (family, method). "
           "Per-ray cost: one core with one slot, cycles per ray = total cycles / rays (no overlap). "
           f"Throughput cost: the `{spec.get('preset', 'small')}` preset, cycles per ray = total cycles / rays "
           "over each trace's whole run, filling and draining the slots included.", ""]
    for title, pick in (("one core, one slot: cycles per ray", lambda r: r["one_core_one_slot"]["cycles_per_ray"]),
                        (f"{spec.get('preset', 'small')} preset: cycles per ray", lambda r: r["cycles_per_ray"])):
        body = []
        for m in spec["methods"]:
            at = {r["family"]: r for r in family_rows if r["method"] == m}
            body.append([f"`{m}`"] + [pick(at[f]) for f in families])
        out += [f"**{title}**", ""] + table(["method"] + families, body) + [""]
    return out


def intro(definition, trace, rows, preset_rows, family_rows):
    """What this run did and how its figures are defined; nothing about the model's
    workings (docs/hw-model.md says those)."""
    spec = definition["trace"]
    out = []
    if rows or preset_rows:
        rays = (rows or preset_rows)[0]["rays"]
        made = (f", generated by `vbsim gen {spec['scenario']} --rays {spec['rays']} --seed {spec['seed']}`"
                if "scenario" in spec else "")
        out += [f"Sweep trace: `{trace}` ({rays} rays{made}).", ""]
    if rows:
        out += [f"Method `{definition.get('method', 'none')}` unless a chart varies it.", ""]
    if rows or preset_rows:
        out += ["Rays per cycle: rays / cycles of each point's cycle-level replay (`hw.rays_per_cycle`). "
                "Analytic bound: the throughput bound of docs/hw-model.md with the operations per ray "
                "measured at that point. Stall shares: `hw.stalls.share_of_slot_cycles`, slot-cycles spent "
                "waiting as a share of all slot-cycles (docs/hw-model.md names the causes).", ""]
    counts = [f"{len(rows)} sweep points" if rows else "", f"{len(preset_rows)} preset runs" if preset_rows else "",
              f"{len(family_rows)} (family, method) rows" if family_rows else ""]
    out.append("This run: " + ", ".join(c for c in counts if c) + ".")
    return out


def write_page(path, command, intro_lines, sections, prov=None):
    lines = ["# Architecture studies with the cycle-level model", "",
             "Generated by `scripts/arch_sweep.py`; do not edit by hand. Regenerate with:", "",
             f"    {command}", ""] + intro_lines + [""]
    for s in sections:
        lines += s
    text = "\n".join(lines).rstrip() + "\n"
    if prov:
        text += "\n" + provenance_comment(prov)
    with open(path, "w") as f:
        f.write(text)
