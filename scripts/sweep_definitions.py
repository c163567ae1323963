"""The stability sweeps that scripts/sweep.py runs.

Each sweep: a scenario of `vbsim gen`, the parameter that varies (`key`: a
`--set` setting of the scenario; or none, when only method arguments vary with
'{x}'), its values, the methods (label and `vbsim replay` arguments), axis
labels, and which end of the range is hard (see sweep_charts.py). A sweep whose
scenario this build lacks is skipped.
"""

def log_range(lo_exp, hi_exp, base=10.0, step=1):
    return [base ** e for e in range(lo_exp, hi_exp + 1, step)]


def method(label, *args):
    return {"label": label, "args": list(args)}


# Methods at their default parameters, for sweeps over a scene parameter.
DEFAULT_METHODS = [
    method("tmin", "-m", "tmin"),
    method("primid", "-m", "primid"),
    method("offset-normal", "-m", "offset-normal"),
    method("offset-adaptive", "-m", "offset-adaptive"),
    method("offset-adaptive+primid", "-m", "offset-adaptive+primid"),
    method("offset-errbound", "-m", "offset-errbound"),
    method("validity-bit all", "-m", "validity-bit", "--vb-policy", "all"),
    method("validity-bit vote", "-m", "validity-bit", "--vb-policy", "vote"),
    method("validity-bit fixed 1e-4", "-m", "validity-bit", "--vb-policy", "vote",
           "--vb-eps-mode", "fixed", "--vb-eps", "1e-4"),
    method("sign-only", "-m", "sign-only"),
]

BUNNY_PATHS = {"scenario": "paths", "rays": 200, "seed": 1}

SWEEPS = [
    {
        "name": "epsilon-size", **BUNNY_PATHS,
        "title": "Epsilon or offset size (bunny, multi-bounce paths)",
        "about": "The bundled bunny (about 10 units across) with diffuse, reflection, "
                 "refraction and shadow children. Each method's distance parameter in "
                 "scene units: too small re-hits the parent, too large skips real geometry.",
        "values": log_range(-8, 0), "xlog": True, "hard": "both",
        "xlabel": "epsilon or offset (scene units)", "unit": "",
        "methods": [
            method("tmin", "-m", "tmin", "--tmin-eps", "{x}"),
            method("offset-normal", "-m", "offset-normal", "--offset-normal-eps", "{x}"),
            method("offset-direction", "-m", "offset-direction", "--offset-direction-eps", "{x}"),
            method("validity-bit all, fixed", "-m", "validity-bit", "--vb-policy", "all",
                   "--vb-eps-mode", "fixed", "--vb-eps", "{x}"),
            method("validity-bit vote, fixed", "-m", "validity-bit", "--vb-policy", "vote",
                   "--vb-eps-mode", "fixed", "--vb-eps", "{x}"),
        ],
    },
    {
        "name": "guard-bits", **BUNNY_PATHS,
        "title": "Guard band of the exponent-derived epsilon (bunny paths)",
        "about": "The patent's dynamic epsilon, 2^(E - 23 + guard) with E the largest "
                 "exponent of the candidate's coordinates; the minimum exponent is set to 1 "
                 "so that the guard band alone sets epsilon.",
        "values": list(range(0, 17)), "xlog": False, "hard": "both",
        "xlabel": "guard bits", "unit": "bits",
        "methods": [
            method("validity-bit all", "-m", "validity-bit", "--vb-policy", "all",
                   "--vb-min-exponent", "1", "--vb-guard-bits", "{x}"),
            method("validity-bit vote", "-m", "validity-bit", "--vb-policy", "vote",
                   "--vb-min-exponent", "1", "--vb-guard-bits", "{x}"),
            method("validity-bit vote, normal test only", "-m", "validity-bit",
                   "--vb-policy", "vote", "--vb-tests", "normal",
                   "--vb-min-exponent", "1", "--vb-guard-bits", "{x}"),
        ],
    },
    {
        "name": "adaptive-scale", **BUNNY_PATHS,
        "title": "Offset scale of the adaptive offset (bunny paths)",
        "about": "Ray Tracing Gems Listing 6-1 with int_scale (ulps per unit normal "
                 "component) varied; the chapter's value is 256.",
        "values": [2 ** k for k in range(0, 17)], "xlog": True, "xbase": 2, "hard": "both",
        "xlabel": "int_scale (ulps)", "unit": "ulps",
        "methods": [
            method("offset-adaptive", "-m", "offset-adaptive", "--adaptive-int-scale", "{x}"),
            method("offset-adaptive+primid", "-m", "offset-adaptive+primid",
                   "--adaptive-int-scale", "{x}"),
        ],
    },
]
