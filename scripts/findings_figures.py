"""Every numeric figure docs/findings.md quotes, with where it comes from.

Each `Figure` is a QUOTE of findings.md (whitespace as one space, `{}` where a figure
stands) and a SOURCE returning the figure's value (a number, or a tuple for several
`{}`), read from a committed result file of docs/results/ or from a vbsim command.
`full=True` marks a source too costly for the quick check (ctest): it runs only in the
full check, which scripts/make_results.sh calls at its end. Each `NotAFigure` quotes
numbers that are inputs or names (a seed, a preset's size, a listing's number), with
the reason. scripts/check_findings.py fails on any number of findings.md that no entry
covers, so a figure added to the page must be added here.
"""
import json
import os

from findings_sources import ROOT, STUDY, Command, SourceError, cell, regex, study, study_rows, sweep_rows, table_cell


class Figure:
    def __init__(self, quote, source, full=False):
        self.quote, self.source, self.full = quote, source, full


class NotAFigure:
    def __init__(self, quote, reason):
        self.quote, self.reason = quote, reason


VB = "validity-bit"
VOTE = "validity-bit:vb-policy=vote"
VB_VARIANTS = [VB, VOTE, "validity-bit:vb-guard-bits=2", "validity-bit:vb-eps-mode=fixed:vb-eps=1e-4",
               "validity-bit:vb-eps-mode=fixed:vb-eps=1e-4:vb-policy=vote"]
OFFSETS = ["offset-normal", "offset-direction", "offset-adaptive", "offset-errbound"]
# The methods that act on every secondary ray (with the presets' shader cores none binds the ray source).
CHEAP_AT_EMISSION = ["tmin", "primid"] + OFFSETS + VB_VARIANTS + ["sign-only"]
# The methods of architecture.md's methods table.
ARCH_METHODS = ["tmin", "primid", "offset-normal", "offset-adaptive", "offset-errbound", "validity-bit",
                "validity-bit:vb-policy=vote", "sign-only"]


def acc(method, family):  # secondary errors per million, three-half-plane tester
    return cell("accuracy.md", "Summary, three-half-plane tester", method, family)


def accp(method, family):  # the same with pbrt-v4's tester
    return cell("accuracy.md", "Summary, pbrt-watertight tester", method, family)


def camp(method, family):  # camera rays pbrt's tester missed, per million
    return cell("accuracy.md", "Camera rays the pbrt-watertight tester missed", method, family)


def preset_field(preset, *path):  # a field of a shipped preset file
    with open(os.path.join(ROOT, "model", "hw", "presets", preset + ".json")) as f:
        value = json.load(f)
    for key in path:
        value = value[key]
    return value


def cycles(method, family="paths"):  # accuracy.md's cycle table, small preset
    return cell("accuracy.md", "Cycles per ray, small preset", method, family)


def arch_methods(method, column):
    return cell("architecture.md", "Methods: cycles per ray and bits per ray", method, column)


def preset(name, trace, memory, deps, column):
    return cell("architecture.md", "What the presets predict", (name, trace, memory, deps), column)


def preset_limit(name, trace, memory, deps, pattern):
    text = table_cell("architecture.md", "What the presets predict", (name, trace, memory, deps),
                      "what limits it")
    return regex("architecture.md", pattern, text)


BUNDLED, SWEEP = "bundled bunny (1008 rays)", "paths 5000 (sweep trace)"


def emission(heading, row, column):
    return cell("architecture.md", heading, row, column)


def breakdown(section, method, pattern):
    return regex("stability.md", pattern,
                 table_cell("stability.md", section, method, "breakdown point"))


def stab(section, method, column, pattern=r"(\S+)"):
    return regex("stability.md", pattern, table_cell("stability.md", section, method, column))


def pbrt_row(method, tester, column, size="At pbrt's size", part=0):
    """pbrt-protocol.md: 'N of M: R [L, U] per million' cells; PART 0 N, 1 M, 2 R, 3 L, 4 U."""
    text = table_cell("pbrt-protocol.md", size, (method, tester), column)
    nums = [float(x.replace(",", "")) for x in
            __import__("re").findall(r"[0-9][0-9,]*(?:\.[0-9]+)?", text)]
    return nums[part]


# The validity-bit study (docs/results/validity-bit-study/: `vbsim explore` rows).
STUDY_REPORT = os.path.join(STUDY, "report.md")
WUSON = "wuson-239k-pathtracer"
VB_ALL, VB_VOTE = "validity-bit (all)", "validity-bit (vote)"
STUDY_OFFSETS = ["offset-adaptive", "offset-errbound", "offset-errbound (pbrt-watertight)"]
STUDY_SOFTWARE = ["tmin"] + STUDY_OFFSETS
STUDY_METHODS = ["primid"] + STUDY_SOFTWARE + [VB_ALL, VB_VOTE]
BARE = dict(cores=4, shader__cores=0, source__emission_width=1)  # the emission unit alone, one lane wide
SHADED = dict(cores=4, shader__cores=4)  # the emission arithmetic on the shader cores
PRESET_LIKE = dict(SHADED, source__emission_width=8, avoidance__share=1, avoidance__issue_interval=1)
# On the preset-like design (4 cores, 4 shader cores, an emission unit 8 wide): one avoidance
# pipeline per core; issuing every 8th cycle; shared by 4 cores; both.
AVOID = [dict(cores=4, shader__cores=4, source__emission_width=8, avoidance__share=s, avoidance__issue_interval=i) for s, i in ((1, 1), (1, 8), (4, 1), (4, 8))]


def study_values(knob):
    """The values the study gives KNOB, ascending."""
    return tuple(sorted({float(r[knob]) for r in study_rows()}))


def worst_software_gap(workload):
    """The largest |cycles / primid's - 1| of the software methods on the shader cores, percent."""
    primid = study(workload, "primid", "cycles_per_ray", cores=4)
    return max(abs(pct(study(workload, m, "cycles_per_ray", **SHADED) / primid - 1)) for m in STUDY_SOFTWARE)


def sensitivity_cell(method, knob):
    """KNOB's main effect on METHOD's cycles per ray, percent, as the study's report.md tabulates it."""
    import explore_analysis
    rows = [{**r, "cycles_per_ray": float(r["cycles_per_ray"])} for r in study_rows()]
    columns = list(rows[0])
    knobs = columns[columns.index("preset") + 1:columns.index("area_mm2")]  # points.csv: the knobs sit between
    return pct(explore_analysis.sensitivity(rows, knobs, "cycles_per_ray")[method][knob])


def study_numeric(workload):
    return [{**r, **{k: float(r[k]) for k in ("area_mm2", "mrays_per_s", "energy_pj_per_ray")}}
            for r in study_rows() if r["workload"] == workload]


def iso_area_span(workload):
    """The default budgets and, at each, the slowest and fastest method's best Mrays/s."""
    import explore_analysis
    rows = study_numeric(workload)
    out = []
    for entry in explore_analysis.iso_area(rows, explore_analysis.default_budgets(rows)):
        speeds = [r["mrays_per_s"] for r in entry["best"].values()]
        out.append((entry["budget_mm2"], min(speeds), max(speeds)))
    (b1, lo1, hi1), (b2, lo2, hi2) = out
    return (b1, lo1, hi1, lo2, hi2, b2)


def iso_throughput_area_spread(workload):
    """The largest area spread between the methods' smallest designs at the default
    targets, pbrt's tester apart."""
    import explore_analysis
    rows = study_numeric(workload)
    spreads = []
    for entry in explore_analysis.iso_throughput(rows, explore_analysis.default_targets(rows)):
        areas = [r["area_mm2"] for m, r in entry["smallest"].items() if m != "offset-errbound (pbrt-watertight)"]
        spreads.append(max(areas) - min(areas))
    return max(spreads)


def study_errors(workload, method, interval=False):
    """Secondary errors per million (with the 95% interval's ends), the same in every design."""
    figures = ("errors_per_million", "ci95_low", "ci95_high") if interval else ("errors_per_million",)
    return tuple(study(workload, method, f) for f in figures)


def same(*values):
    """The one value several figures share (a SourceError when they differ)."""
    if len(set(values)) != 1:
        raise SourceError(f"expected equal figures, got {values}")
    return values[0]


def pct(x):
    return 100.0 * x


def loss(on, off):  # how much slower dependencies make a run, percent
    return 100.0 * (1.0 - on / off)


def ops(method, part, vbsim):
    """The method's operations (config.cost_ops) from `vbsim score` on the bundled trace."""
    for row in bunny_score(vbsim).json()["rows"]:
        if row["method"] == method and row["tester"] == "three-half-plane" and row["kind"] == "all":
            return row["config"]["cost_ops"][part] if part != "ops_per_ray" else row["ops_per_ray"]
    raise KeyError(method)


def bunny_score(vbsim):
    return Command(vbsim, ["score", "traces/bunny", "--testers", "three-half-plane", "--out", "{out}"],
                   out_json=True)


def bunny_energy(method, field, vbsim):
    for row in bunny_score(vbsim).json()["rows"]:
        if row["method"] == method and row["tester"] == "three-half-plane" and row["kind"] == "all":
            return row["energy"][field]
    raise KeyError(method)


def area(method, instance, vbsim):
    text = Command(vbsim, ["hw", "--area", "--preset", "small", "-m", method]).text()
    return regex("", r"\n\s*" + instance + r"\s+\S+\s+\d+\s+([0-9.]+)", text)


def bench_200k(vbsim):
    return Command(vbsim, ["bench", "--mode", "cycle", "--rays", "200000", "--repeats", "1",
                           "--json", "{out}"], out_json=True).json()


def reintersect(vbsim):
    """pbrt-v4's protocol at pbrt's size rerun in process (`vbsim reintersect`, about 2 s)."""
    return Command(vbsim, ["reintersect", "-q", "--triangles", "1000", "--methods",
                           "offset-errbound,offset-adaptive,validity-bit,validity-bit:vb-policy=vote,sign-only",
                           "--testers", "pbrt-watertight,three-half-plane", "--json", "{out}"], out_json=True).json()


def rerun_pbrt(method, tester, field="count", vbsim=None):
    """A children count (or 'rate' per million, 'of') of the rerun at pbrt's size."""
    for row in reintersect(vbsim)["rows"]:
        if row["method"] == method and row["tester"] == tester:
            return row["children"][field]
    raise KeyError(f"{method}/{tester}")


_paths_dir = []


def paths_score(vbsim):
    """The `paths` family regenerated as make_results.sh does (10000 rays, seed 1) and
    scored in cycle mode on the small preset, three-half-plane tester (about a minute)."""
    import tempfile
    if not _paths_dir:
        import atexit
        import shutil
        _paths_dir.append(tempfile.mkdtemp(prefix="check_findings_paths_"))
        atexit.register(shutil.rmtree, _paths_dir[0], True)
    d = _paths_dir[0]
    Command(vbsim, ["gen", "paths", "--rays", "10000", "--seed", "1", "-q", "-o", d + "/paths"]).text()
    return Command(vbsim, ["score", d + "/paths", "--testers", "three-half-plane", "--mode", "cycle",
                           "--preset", "small", "--cycle-testers", "three-half-plane", "--out", "{out}"],
                   out_json=True).json()


def rerun_paths(method, what, vbsim):
    """'errors': secondary errors per million; 'cycles': cycles per ray (all rays)."""
    for row in paths_score(vbsim)["rows"]:
        if row["method"] != method or row["tester"] != "three-half-plane":
            continue
        if what == "errors" and row["kind"] == "secondary":
            return row["errors"]["per_million"]["rate"]
        if what == "cycles" and row["kind"] == "all":
            return row["cycle"]["cycles_per_ray"]
    raise KeyError(f"{method}/{what}")


def far_k():
    """k of the far-instance family's trace (far-instance-kK.jsonl, architecture.md's inputs)."""
    return regex("architecture.md", r"far-instance-k([0-9]+)\.jsonl")


def int_scale(vbsim):
    """offset-adaptive's int_scale (ulps per unit normal component) as vbsim score runs it."""
    for row in bunny_score(vbsim).json()["rows"]:
        if row["method"] == "offset-adaptive":
            return row["config"]["adaptive"]["int_scale"]
    raise KeyError("offset-adaptive")


def bundled_paths(vbsim):
    import json
    import os
    from findings_sources import ROOT
    with open(os.path.join(ROOT, "traces", "bunny", "paths.jsonl")) as f:
        rays = [json.loads(l) for l in f if l.strip()]
    # A path starts at a camera ray: a ray without a parent (the header has no id).
    return sum(1 for r in rays if "id" in r and r.get("parent", -1) == -1)


def FIGURES(vbsim):
    v = vbsim
    return [
        # The page's own conventions.
        NotAFigure("seed 1, 10000 rays per scenario", "make_results.sh's inputs"),
        NotAFigure("95% interval", "the confidence level"),
        # Where each method breaks: tmin.
        Figure("holds on the `paths` family ({} per million)", lambda: acc("tmin", "paths")),
        Figure("re-hits on the random triangles ({} on the Ray Tracing Gems set)",
               lambda: acc("tmin", "random-triangles-rtg")),
        Figure("leaks at every crevice angle up to {} degrees ({})",
               lambda: (breakdown("Opening angle of a crevice", "tmin", r"([0-9.]+) deg and below"),
                        acc("tmin", "crevice"))),
        Figure("skips the adjacent wall of box corners ({})", lambda: acc("tmin", "corner")),
        Figure("leaks through layers closer than {} times its epsilon",
               lambda: breakdown("Separation of parallel layers", "tmin", r"([0-9.]+) x offset and below")),
        Figure("it misses {} per million camera rays",
               lambda: cell("accuracy.md", "Camera rays the three-half-plane tester missed", "tmin",
                            "random-triangles-rtg")),
        Figure("error-free window only from {} to {} scene units",
               lambda: (breakdown("Epsilon or offset size", "tmin", r"from ([0-9.e-]+) to"),
                        breakdown("Epsilon or offset size", "tmin", r"to ([0-9.e-]+)$"))),
        # primid.
        Figure("convex geometry ({} on the bunny paths, Wuson and all three random-triangle sets)",
               lambda: max(acc("primid", f) for f in ["paths", "paths-wuson", "random-triangles-rtg",
                                                      "random-triangles-pbrt", "random-triangles-pbrt-v4"])),
        Figure("as expected: {} per million on `shared-edges`, {} on `grazing`, {} on duplicated coplanar",
               lambda: (acc("primid", "shared-edges"), acc("primid", "grazing"), acc("primid", "coplanar"))),
        # Fixed offsets.
        Figure("`offset-normal` has errors at every translation from 2^{} up, `tmin` from 2^{})",
               lambda: (breakdown("A mesh 2^k from the origin", "offset-normal", r"(-?[0-9]+) and above"),
                        breakdown("A mesh 2^k from the origin", "tmin", r"(-?[0-9]+) and above"))),
        Figure("in crevices ({} and {} per million, nearly all missed)",
               lambda: (acc("offset-normal", "crevice"), acc("offset-direction", "crevice"))),
        # offset-adaptive.
        NotAFigure("(Ray Tracing Gems Listing 6-1)", "a listing's number"),
        Figure("{} on its Figure 6-7 triangles at every distance (2^-{} to 2^{}) and every size",
               lambda: (sum(int(r[k]) for s in ("distance", "triangle-size")
                            for r in sweep_rows(s, "offset-adaptive")
                            for k in ("self_hit", "false_hit", "missed")),
                        -min(float(r["x"]) for r in sweep_rows("distance", "offset-adaptive")),
                        max(float(r["x"]) for r in sweep_rows("distance", "offset-adaptive")))),
        NotAFigure("its Figure 6-7 triangles", "a figure's number in Ray Tracing Gems"),
        Figure("on a bunny translated 2^{} away its {} ulps are {} units",
               lambda: (far_k(), int_scale(v), int_scale(v) * 2.0 ** (far_k() - 23))),
        Figure("children skip the mesh (far-instance {}, almost all misses)",
               lambda: acc("offset-adaptive", "far-instance")),
        NotAFigure("coordinate range (10^±8)", "pbrt-v4's protocol definition"),
        Figure("it re-hits: {} per million on pbrt-v4's own protocol with the three-half-plane tester, {} with pbrt's tester",
               lambda: (acc("offset-adaptive", "random-triangles-pbrt-v4"),
                        accp("offset-adaptive", "random-triangles-pbrt-v4"))),
        Figure("at pbrt's full size ({} triangles, {} children each) {} of {} children, all of them `SpawnRayTo` rays",
               lambda: (regex("pbrt-protocol.md", r"\n([0-9]+) triangles RNG\(0\) \.\. RNG\(999\)"),
                        2 * regex("pbrt-protocol.md", r"RNG\(999\), ([0-9]+) SpawnRay and"),
                        pbrt_row("offset-adaptive", "pbrt-watertight", "children re-hit"),
                        pbrt_row("offset-adaptive", "pbrt-watertight", "children re-hit", part=1))),
        # offset-errbound.
        Figure("no re-hit of the {} children at pbrt's size and {} of {} at {} times it (all {} `SpawnRayTo` rays; {} per million, 95% interval {} to {})",
               lambda: (pbrt_row("offset-errbound", "pbrt-watertight", "children re-hit", part=1),
                        pbrt_row("offset-errbound", "pbrt-watertight", "children re-hit", "At 100 times"),
                        pbrt_row("offset-errbound", "pbrt-watertight", "children re-hit", "At 100 times", 1),
                        100,
                        pbrt_row("offset-errbound", "pbrt-watertight", "SpawnRayTo re-hit", "At 100 times"),
                        pbrt_row("offset-errbound", "pbrt-watertight", "children re-hit", "At 100 times", 2),
                        pbrt_row("offset-errbound", "pbrt-watertight", "children re-hit", "At 100 times", 3),
                        pbrt_row("offset-errbound", "pbrt-watertight", "children re-hit", "At 100 times", 4))),
        Figure("the same origins re-hit {}% of the children ({} of {})",
               lambda: (pct(pbrt_row("offset-errbound", "three-half-plane", "children re-hit") /
                            pbrt_row("offset-errbound", "three-half-plane", "children re-hit", part=1)),
                        pbrt_row("offset-errbound", "three-half-plane", "children re-hit"),
                        pbrt_row("offset-errbound", "three-half-plane", "children re-hit", part=1))),
        Figure("and {} per million on the pbrt-v4 family", lambda: acc("offset-errbound", "random-triangles-pbrt-v4")),
        Figure("pbrt's test skips {}% of its triangles ({} of {} at {} times its size)",
               lambda: (pct(regex("pbrt-protocol.md", r"100000 triangles.*?, ([0-9]+) skipped") /
                            (100000 - regex("pbrt-protocol.md", r"100000 triangles.*?: ([0-9]+) dropped"))),
                        regex("pbrt-protocol.md", r"100000 triangles.*?, ([0-9]+) skipped"),
                        100000 - regex("pbrt-protocol.md", r"100000 triangles.*?: ([0-9]+) dropped"),
                        100)),
        Figure("on the pbrt-v4 family {} per million camera rays are missed where the exact answer is a hit, {} on the Ray Tracing Gems set",
               lambda: (camp("offset-errbound", "random-triangles-pbrt-v4"),
                        camp("offset-errbound", "random-triangles-rtg"))),
        Figure("`offset-errbound` goes from {} per million with the three-half-plane tester to {} with pbrt's",
               lambda: (acc("offset-errbound", "corner"), accp("offset-errbound", "corner"))),
        Figure("every method but `reverse-shadow` is at {} or more there",
               lambda: min(accp(m, "corner") for m in
                           ["none", "tmin", "primid", "tmin+primid"] + OFFSETS + ["offset-adaptive+primid"] +
                           VB_VARIANTS + ["sign-only", "shading-position", "shading-position-always",
                                          "shading-position+offset-adaptive"])),
        Figure("`offset-errbound` has {} per million with the three-half-plane tester (pbrt's point is not the trace's point) and {} on the Ray Tracing Gems triangles",
               lambda: (acc("offset-errbound", "paths"), acc("offset-errbound", "random-triangles-rtg"))),
        # Thin crevice.
        Figure("at {} degree, {}% and {}% of the rays are wrong with `offset-normal` and `offset-adaptive`, {}% with `offset-errbound`",
               lambda: (1,) + tuple(pct(stab("Opening angle of a crevice", m, "worst rate", r"([0-9.]+) at 1 deg"))
                                    for m in ("offset-normal", "offset-adaptive", "offset-errbound"))),
        # The validity bit: policy all.
        Figure("(grazing {} per million, shared-edges {}; the sweep shows errors up to {} rad)",
               lambda: (acc(VB, "grazing"), acc(VB, "shared-edges"),
                        breakdown("Grazing angle", "validity-bit all", r"([0-9.]+) rad and below"))),
        # vote.
        Figure("Wuson and the Ray Tracing Gems triangles ({} each)",
               lambda: max(acc(VOTE, f) for f in ["paths", "paths-wuson", "random-triangles-rtg"])),
        Figure("{} per million on the signed pbrt set, {} on pbrt-v4's",
               lambda: (acc(VOTE, "random-triangles-pbrt"), acc(VOTE, "random-triangles-pbrt-v4"))),
        Figure("it re-hits {} of {} children ({} per million) even with pbrt's tester, {} ({} per million) with the three-half-plane tester",
               lambda: (pbrt_row(VOTE, "pbrt-watertight", "children re-hit"),
                        pbrt_row(VOTE, "pbrt-watertight", "children re-hit", part=1),
                        pbrt_row(VOTE, "pbrt-watertight", "children re-hit", part=2),
                        pbrt_row(VOTE, "three-half-plane", "children re-hit"),
                        pbrt_row(VOTE, "three-half-plane", "children re-hit", part=2))),
        Figure("On grazing children it has {} times the errors of `offset-errbound` (grazing: vote {}, `offset-errbound` {}, `sign-only` {}), fewer than `offset-adaptive` ({}), `primid` ({}) and policy all ({})",
               lambda: (acc(VOTE, "grazing") / acc("offset-errbound", "grazing"), acc(VOTE, "grazing"),
                        acc("offset-errbound", "grazing"), acc("sign-only", "grazing"),
                        acc("offset-adaptive", "grazing"), acc("primid", "grazing"), acc(VB, "grazing"))),
        Figure("crevices and corners ({}, {}) are shared", lambda: (acc(VOTE, "crevice"), acc(VOTE, "corner"))),
        # Exponent-derived epsilon and fixed epsilon.
        Figure("error-free from {} guard bits (policy all) or {} (vote)",
               lambda: (breakdown("Guard band", "validity-bit all", r"from ([0-9]+) bits"),
                        breakdown("Guard band", "validity-bit vote", r"from ([0-9]+) bits"))),
        NotAFigure("the patent's 4-5 bits", "the patent's statement"),
        NotAFigure("A **fixed** 1e-4 epsilon", "a configuration value"),
        Figure("fails on the random triangles ({}) and leaks through layers closer than 1e-4 ({})",
               lambda: (acc("validity-bit:vb-eps-mode=fixed:vb-eps=1e-4", "random-triangles-rtg"),
                        acc("validity-bit:vb-eps-mode=fixed:vb-eps=1e-4", "layers"))),
        NotAFigure("layers closer than 1e-4", "a configuration value"),
        # sign-only.
        Figure("every decal-on-wall layer ({})", lambda: acc("sign-only", "layers")),
        Figure("fails on Wuson's paths ({} per million, where vote has {})",
               lambda: (acc("sign-only", "paths-wuson"), acc(VOTE, "paths-wuson"))),
        Figure("close to vote ({} against {} on the signed pbrt set, {} against {} on shared edges, {} against {} on grazing)",
               lambda: (acc("sign-only", "random-triangles-pbrt"), acc(VOTE, "random-triangles-pbrt"),
                        acc("sign-only", "shared-edges"), acc(VOTE, "shared-edges"),
                        acc("sign-only", "grazing"), acc(VOTE, "grazing"))),
        Figure("it re-hits {} of {} children with pbrt's tester",
               lambda: (pbrt_row("sign-only", "pbrt-watertight", "children re-hit"),
                        pbrt_row("sign-only", "pbrt-watertight", "children re-hit", part=1))),
        Figure("({} errors on `refraction`)", lambda: max(acc(m, "refraction") for m in VB_VARIANTS + ["sign-only"])),
        # Costs.
        Figure("Bits per ray in flight: {} for every offset, {} with the sign bit, {} with the parent triangle id",
               lambda: (arch_methods("offset-errbound", "bits/ray"), arch_methods(VB, "bits/ray"),
                        arch_methods("primid", "bits/ray"))),
        Figure("Operations at emission: {} (`tmin`) to {} (`shading-position+offset-adaptive`; {} for `offset-errbound`",
               lambda: (ops("tmin", "emission", v), ops("shading-position+offset-adaptive", "emission", v),
                        ops("offset-errbound", "emission", v))),
        Figure("the avoidance unit costs {} per candidate and {} per suspect ({} with a fixed epsilon)",
               lambda: (ops(VB, "candidate", v), ops(VB, "suspect", v),
                        ops("validity-bit:vb-eps-mode=fixed:vb-eps=1e-4", "suspect", v))),
        Figure("which on the `paths` family is {} operations per ray",
               lambda: cell("accuracy.md", "paths", (VB, "three-half-plane"), "ops/ray")),
        NotAFigure("the shipped 45 nm figures", "the technology file's node"),
        Figure("the validity bit's own arithmetic costs {} pJ per ray (its four avoidance units {} mm² on the `small` preset), `offset-errbound`'s {} pJ (a {} mm² emission lane, its operators shared by the unit {} wide), against about {} nJ per ray of traversal operations",
               lambda: (bunny_energy(VB, "method_per_ray_pj", v),
                        area(VB, "avoidance_unit", v),
                        bunny_energy("offset-errbound", "method_per_ray_pj", v),
                        area("offset-errbound", "emission_lane", v), preset_field("small", "source", "emission_width"),
                        (bunny_energy(VB, "per_ray_pj", v) - bunny_energy(VB, "method_per_ray_pj", v)) / 1000)),
        Figure("the caches and DRAM dominate ({} nJ per ray on {} random bunny rays, {} Mrays/J)",
               lambda: (bench_200k(v)["hw"]["energy"]["per_ray_pj"] / 1000, bench_200k(v)["rays"],
                        bench_200k(v)["hw"]["energy"]["mrays_per_j"]), full=True),
        # Cycles.
        Figure("`sign-only` cost {} to {} cycles per ray, `none` {} only",
               lambda: (min(cycles(m) for m in CHEAP_AT_EMISSION),
                        max(cycles(m) for m in CHEAP_AT_EMISSION),
                        cycles("none"))),
        NotAFigure("at the 33 cycles its arithmetic gives", "docs/hw-model.md's derivation, pinned by "
                   "testbench/unit/tester_timing_test.cpp"),
        Figure("which act on shadow rays only, {} to {}",
               lambda: (min(cycles(m) for m in ["shading-position", "shading-position-always", "reverse-shadow"]),
                        max(cycles(m) for m in ["shading-position", "shading-position-always", "reverse-shadow"]))),
        Figure("On the `large` preset the same methods cost {} to {} cycles per ray",
               lambda: (min(arch_methods(m, "cycles/ray: large preset") for m in ARCH_METHODS),
                        max(arch_methods(m, "cycles/ray: large preset") for m in ARCH_METHODS))),
        Figure("and on one core with one slot {} to {}",
               lambda: (min(arch_methods(m, "cycles/ray: 1 core x 1 slot") for m in ARCH_METHODS),
                        max(arch_methods(m, "cycles/ray: 1 core x 1 slot") for m in ARCH_METHODS))),
        # Child rays that wait for their parents.
        NotAFigure("(`shader.latency_cycles`, 200 by default;", "a configuration default (docs/hw-model.md)"),
        NotAFigure("(4 cores x 32 slots)", "the small preset's definition"),
        NotAFigure("(10 cores x 128 slots, a ray source of one ray per cycle)", "the large preset's definition"),
        Figure("on the {}-ray sweep trace, whose {} paths", lambda: (preset("small", SWEEP, "hierarchy", "on", "rays"),
                        regex("architecture.md", r"vbsim gen paths --rays ([0-9]+)"))),
        Figure("{} against {} rays per cycle with the memory hierarchy (-{}%), {} against {} with ideal memory; mean latency {} against {} cycles",
               lambda: (preset("small", SWEEP, "hierarchy", "on", "rays/cycle"), preset("small", SWEEP, "hierarchy", "off", "rays/cycle"),
                        loss(preset("small", SWEEP, "hierarchy", "on", "rays/cycle"), preset("small", SWEEP, "hierarchy", "off", "rays/cycle")),
                        preset("small", SWEEP, "ideal", "on", "rays/cycle"), preset("small", SWEEP, "ideal", "off", "rays/cycle"),
                        preset("small", SWEEP, "hierarchy", "on", "mean latency"), preset("small", SWEEP, "hierarchy", "off", "mean latency"))),
        Figure("On the {}-ray bundled trace the hierarchy runs *faster* with dependencies ({} against {} rays per cycle, mean latency {} against {})",
               lambda: (preset("small", BUNDLED, "hierarchy", "on", "rays"),
                        preset("small", BUNDLED, "hierarchy", "on", "rays/cycle"), preset("small", BUNDLED, "hierarchy", "off", "rays/cycle"),
                        preset("small", BUNDLED, "hierarchy", "on", "mean latency"), preset("small", BUNDLED, "hierarchy", "off", "mean latency"))),
        Figure("(L2 hit rate {} against {}; {} against {} cycles per line request)",
               lambda: (preset("small", BUNDLED, "hierarchy", "on", "L2 hit"), preset("small", BUNDLED, "hierarchy", "off", "L2 hit"),
                        preset_limit("small", BUNDLED, "hierarchy", "on", r"([0-9.]+) cycles per line"),
                        preset_limit("small", BUNDLED, "hierarchy", "off", r"([0-9.]+) cycles per line"))),
        Figure("With ideal memory it is {}% slower ({} against {})",
               lambda: (loss(preset("small", BUNDLED, "ideal", "on", "rays/cycle"), preset("small", BUNDLED, "ideal", "off", "rays/cycle")),
                        preset("small", BUNDLED, "ideal", "on", "rays/cycle"), preset("small", BUNDLED, "ideal", "off", "rays/cycle"))),
        Figure("the lanes sit idle for parents {}% of their cycles",
               lambda: pct(preset("small", BUNDLED, "ideal", "on", "lanes idle for parents"))),
        Figure("{} against {} rays per cycle on the sweep trace (-{}%), {} against {} on the bundled trace (-{}%: its {} rays are {} paths",
               lambda: (preset("large", SWEEP, "ideal", "on", "rays/cycle"), preset("large", SWEEP, "ideal", "off", "rays/cycle"),
                        loss(preset("large", SWEEP, "ideal", "on", "rays/cycle"), preset("large", SWEEP, "ideal", "off", "rays/cycle")),
                        preset("large", BUNDLED, "ideal", "on", "rays/cycle"), preset("large", BUNDLED, "ideal", "off", "rays/cycle"),
                        loss(preset("large", BUNDLED, "ideal", "on", "rays/cycle"), preset("large", BUNDLED, "ideal", "off", "rays/cycle")),
                        preset("large", BUNDLED, "ideal", "on", "rays"), bundled_paths(v))),
        Figure("With the memory hierarchy, {} against {} on the sweep trace (-{}%) and mean latency {} against {} cycles",
               lambda: (preset("large", SWEEP, "hierarchy", "on", "rays/cycle"), preset("large", SWEEP, "hierarchy", "off", "rays/cycle"),
                        loss(preset("large", SWEEP, "hierarchy", "on", "rays/cycle"), preset("large", SWEEP, "hierarchy", "off", "rays/cycle")),
                        preset("large", SWEEP, "hierarchy", "on", "mean latency"), preset("large", SWEEP, "hierarchy", "off", "mean latency"))),
        Figure("(memory wait {}% of slot-cycles against {}%, {} against {} cycles per line request)",
               lambda: (preset_limit("large", SWEEP, "hierarchy", "on", r"memory wait takes ([0-9]+)%"),
                        preset_limit("large", SWEEP, "hierarchy", "off", r"memory wait takes ([0-9]+)%"),
                        preset_limit("large", SWEEP, "hierarchy", "on", r"([0-9.]+) cycles per line"),
                        preset_limit("large", SWEEP, "hierarchy", "off", r"([0-9.]+) cycles per line"))),
        Figure("two lanes reach {} rays per cycle for independent rays (bound {}) but {} with dependencies, and more lanes add nothing ({} to {}); with the memory hierarchy {} to {} at any width",
               lambda: (emission("Emission lanes", "2", "rays/cycle: ideal memory, independent rays"),
                        emission("Emission lanes", "2", "analytic bound"),
                        emission("Emission lanes", "2", "rays/cycle: ideal memory, dependencies"),
                        min(emission("Emission lanes", w, "rays/cycle: ideal memory, dependencies") for w in ("4", "8")),
                        max(emission("Emission lanes", w, "rays/cycle: ideal memory, dependencies") for w in ("4", "8")),
                        min(emission("Emission lanes", w, "rays/cycle: memory hierarchy, dependencies") for w in ("1", "2", "4", "8")),
                        max(emission("Emission lanes", w, "rays/cycle: memory hierarchy, dependencies") for w in ("1", "2", "4", "8")))),
        Figure("costs little up to {} cycles (small: {} to {}; large: {} to {}) and a lot beyond on the large preset ({} at {}, {} at {})",
               lambda: (200, emission("Shading latency", "1", "rays/cycle: small preset"),
                        emission("Shading latency", "200", "rays/cycle: small preset"),
                        emission("Shading latency", "1", "rays/cycle: large preset"),
                        emission("Shading latency", "200", "rays/cycle: large preset"),
                        emission("Shading latency", "800", "rays/cycle: large preset"), 800,
                        emission("Shading latency", "3200", "rays/cycle: large preset"), 3200)),
        Figure("on the large preset {} rays per cycle at {}, {} at {}, {} at {} (the default) and {} at {}",
               lambda: (emission("Ray-emission window", "64", "rays/cycle: large preset"), 64,
                        emission("Ray-emission window", "1024", "rays/cycle: large preset"), 1024,
                        emission("Ray-emission window", "4096", "rays/cycle: large preset"), 4096,
                        emission("Ray-emission window", "16384", "rays/cycle: large preset"), 16384)),
        # The full check also reruns what the quick one reads from docs/results: pbrt's
        # protocol at its size and the `paths` family, regenerated and scored.
        Figure("at pbrt's full size ({} triangles, {} children each) {} of {} children, all of them `SpawnRayTo` rays",
               lambda: (reintersect(v)["params"]["triangles"], 2 * reintersect(v)["params"]["children"],
                        rerun_pbrt("offset-adaptive", "pbrt-watertight", vbsim=v),
                        rerun_pbrt("offset-adaptive", "pbrt-watertight", "of", v)), full=True),
        Figure("the same origins re-hit {}% of the children ({} of {})",
               lambda: (pct(rerun_pbrt("offset-errbound", "three-half-plane", vbsim=v) /
                            rerun_pbrt("offset-errbound", "three-half-plane", "of", v)),
                        rerun_pbrt("offset-errbound", "three-half-plane", vbsim=v),
                        rerun_pbrt("offset-errbound", "three-half-plane", "of", v)), full=True),
        Figure("it re-hits {} of {} children ({} per million) even with pbrt's tester, {} ({} per million) with the three-half-plane tester",
               lambda: (rerun_pbrt(VOTE, "pbrt-watertight", vbsim=v), rerun_pbrt(VOTE, "pbrt-watertight", "of", v),
                        rerun_pbrt(VOTE, "pbrt-watertight", "rate", v), rerun_pbrt(VOTE, "three-half-plane", vbsim=v),
                        rerun_pbrt(VOTE, "three-half-plane", "rate", v)), full=True),
        Figure("it re-hits {} of {} children with pbrt's tester",
               lambda: (rerun_pbrt("sign-only", "pbrt-watertight", vbsim=v),
                        rerun_pbrt("sign-only", "pbrt-watertight", "of", v)), full=True),
        Figure("holds on the `paths` family ({} per million)", lambda: rerun_paths("tmin", "errors", v), full=True),
        Figure("`offset-errbound` has {} per million with the three-half-plane tester (pbrt's point is not the trace's point) and {} on the Ray Tracing Gems triangles",
               lambda: (rerun_paths("offset-errbound", "errors", v), acc("offset-errbound", "random-triangles-rtg")),
               full=True),
        Figure("`sign-only` cost {} to {} cycles per ray, `none` {} only",
               lambda: (min(rerun_paths(m, "cycles", v) for m in CHEAP_AT_EMISSION),
                        max(rerun_paths(m, "cycles", v) for m in CHEAP_AT_EMISSION),
                        rerun_paths("none", "cycles", v)), full=True),
        Figure("overstate a path-tracing machine by up to {}% on long traces",
               lambda: max(loss(preset(p, SWEEP, m, "on", "rays/cycle"), preset(p, SWEEP, m, "off", "rays/cycle"))
                           for p in ("small", "large") for m in ("hierarchy", "ideal"))),
        # Does the validity bit pay for itself? (docs/results/validity-bit-study/, vbsim explore)
        NotAFigure("(`results/validity-bit-study/`: `report.md`", "a file name"),
        Figure("Wuson subdivided to {} triangles ({} rays, {} of them secondary",
               lambda: (regex(STUDY_REPORT, r"over Wuson subdivided to ([0-9,]+) triangles"),
                        study(WUSON, "primid", "rays", cores=4), study(WUSON, "primid", "secondary_scored", cores=4))),
        NotAFigure("the bunny 2^20 away", "the far-instance scenario's k (2^20)"),
        NotAFigure("seven methods", "a count of names"),
        NotAFigure("secondary-ray errors per million with 95% intervals", "the intervals' confidence"),
        NotAFigure("2^20 away every method fails", "the far-instance scenario's k (2^20)"),
        NotAFigure("2^20 away, on the shader cores", "the far-instance scenario's k (2^20)"),
        Figure("{} designs of the `small` preset ({} or {} cores; {} or {} shader cores; an emission unit {} or {} operations wide; one avoidance pipeline per core or one shared by {} cores;",
               lambda: (len({r["design"] for r in study_rows()}),) + study_values("cores") + study_values("shader.cores")
               + study_values("source.emission_width") + study_values("avoidance.share")[1:]),
        NotAFigure("priced with the 45 nm technology file", "the technology file's node"),
        Figure("`offset-errbound` costs {} cycles per ray on the Wuson capture and `tmin` {}, against {} for `primid`; on the shader cores they cost {} and {}",
               lambda: (study(WUSON, "offset-errbound", "cycles_per_ray", **BARE), study(WUSON, "tmin", "cycles_per_ray", **BARE),
                        study(WUSON, "primid", "cycles_per_ray", cores=4),
                        study(WUSON, "offset-errbound", "cycles_per_ray", **SHADED),
                        study(WUSON, "tmin", "cycles_per_ray", **SHADED))),
        Figure("every software method is within {}% of `primid` on the capture and {}% on the frame",
               lambda: (worst_software_gap(WUSON), worst_software_gap("bunny-frame"))),
        Figure("the shader cores move `offset-errbound`'s cycles by {}% of their mean and the number of cores moves the validity bit's by {}%",
               lambda: (sensitivity_cell("offset-errbound", "shader.cores"), sensitivity_cell("validity-bit (all)", "cores"))),
        Figure("makes the chip {} mm² against `primid`'s {}; issuing every 8th cycle, {}; one such pipeline shared by four cores, {}, all at the same cycles on the capture ({}, {}, {})",
               lambda: (study(WUSON, VB_ALL, "area_mm2", **AVOID[0]), study(WUSON, "primid", "area_mm2", cores=4),
                        study(WUSON, VB_ALL, "area_mm2", **AVOID[1]), study(WUSON, VB_ALL, "area_mm2", **AVOID[3]),
                        study(WUSON, VB_ALL, "cycles_per_ray", **AVOID[0]), study(WUSON, VB_ALL, "cycles_per_ray", **AVOID[1]),
                        study(WUSON, VB_ALL, "cycles_per_ray", **AVOID[3]))),
        Figure("the shared slow unit doubles the cycles ({} to {}), while the issue interval alone ({}) or the sharing alone ({}) keeps them",
               lambda: tuple(study("nested-spheres", VB_ALL, "cycles_per_ray", **AVOID[i]) for i in (0, 3, 1, 2))),
        Figure("Within {} mm² (the smallest area at which every method has a design) every method's fastest design on the capture runs {} to {} Mrays/s, and {} to {} within {} mm²",
               lambda: iso_area_span(WUSON)),
        Figure("the iso-throughput tables pick designs within {} mm² of each other, but for pbrt's tester, which costs {} mm² more than the three-half-plane tester",
               lambda: (iso_throughput_area_spread(WUSON),
                        study(WUSON, "offset-errbound (pbrt-watertight)", "area_mm2", **PRESET_LIKE)
                        - study(WUSON, "offset-errbound", "area_mm2", **PRESET_LIKE))),
        Figure("on the capture `vote` {} [{}, {}], `primid` {} [{}, {}], `tmin` {}, `offset-adaptive` {}, `offset-errbound` {} with the three-half-plane tester and {} [{}, {}] with pbrt's, policy `all` {} [{}, {}]",
               lambda: study_errors(WUSON, VB_VOTE, True) + study_errors(WUSON, "primid", True)
               + study_errors(WUSON, "tmin") + study_errors(WUSON, "offset-adaptive") + study_errors(WUSON, "offset-errbound")
               + study_errors(WUSON, "offset-errbound (pbrt-watertight)", True) + study_errors(WUSON, VB_ALL, True)),
        Figure("on the closed-loop frame `primid`, `offset-errbound` (both testers) and `vote` {} [{}, {}], `tmin` {}, `offset-adaptive` {}, `all` {}",
               lambda: same(*(study_errors("bunny-frame", m, True) for m in
                              ("primid", "offset-errbound", "offset-errbound (pbrt-watertight)", VB_VOTE)))
               + study_errors("bunny-frame", "tmin") + study_errors("bunny-frame", "offset-adaptive")
               + study_errors("bunny-frame", VB_ALL)),
        Figure("on the nested spheres every method {} but `tmin` ({}: it skips the inner layer)",
               lambda: (max(study_errors("nested-spheres", m)[0] for m in STUDY_METHODS if m != "tmin"),
                        study_errors("nested-spheres", "tmin")[0])),
        Figure("every method fails, the validity bit least (`all` {}, `primid` {}, the offsets {} to {})",
               lambda: (study_errors("far-instance", VB_ALL)[0], study_errors("far-instance", "primid")[0],
                        min(study_errors("far-instance", m)[0] for m in STUDY_OFFSETS),
                        max(study_errors("far-instance", m)[0] for m in STUDY_OFFSETS))),
        Figure("it costs {} mm² ({}%) with a slow avoidance pipeline per core",
               lambda: (study(WUSON, VB_ALL, "area_mm2", **AVOID[1]) - study(WUSON, "primid", "area_mm2", cores=4),
                        pct(study(WUSON, VB_ALL, "area_mm2", **AVOID[1]) / study(WUSON, "primid", "area_mm2", cores=4) - 1))),
        Figure("`offset-errbound` with pbrt's tester is the most accurate method on the capture at {} mm² more",
               lambda: study(WUSON, "offset-errbound (pbrt-watertight)", "area_mm2", **PRESET_LIKE)
               - study(WUSON, "offset-errbound", "area_mm2", **PRESET_LIKE)),
        Figure("`offset-adaptive` runs at {} cycles per ray against `primid`'s {}",
               lambda: (study("far-instance", "offset-adaptive", "cycles_per_ray", **SHADED),
                        study("far-instance", "primid", "cycles_per_ray", cores=4))),
    ]
