"""The stability sweeps that scripts/sweep.py runs.

Each sweep: a scenario of `vbsim gen`, the parameter that varies (`key`: a
`--set` setting of the scenario; or none, when only method arguments vary with
'{x}'), its values, the methods (label and `vbsim replay` arguments), axis
labels, and which end of the range is hard (see sweep_charts.py); `traces`, a
glob of the point's traces to replay (default all). A sweep whose scenario this
build lacks is skipped.
"""

def log_range(lo_exp, hi_exp, base=10.0, step=1):
    return [base ** e for e in range(lo_exp, hi_exp + 1, step)]


def method(label, spec):
    """A line of a chart: its label and its `vbsim score` method entry
    (METHOD[:option=value...], '{x}' replaced by the sweep value)."""
    return {"label": label, "spec": spec}


# Methods at their default parameters, for sweeps over a scene parameter.
DEFAULT_METHODS = [
    method("tmin", "tmin"),
    method("primid", "primid"),
    method("offset-normal", "offset-normal"),
    method("offset-adaptive", "offset-adaptive"),
    method("offset-adaptive+primid", "offset-adaptive+primid"),
    method("offset-errbound", "offset-errbound"),
    method("validity-bit all", "validity-bit:vb-policy=all"),
    method("validity-bit vote", "validity-bit:vb-policy=vote"),
    method("validity-bit fixed 1e-4", "validity-bit:vb-policy=vote:vb-eps-mode=fixed:vb-eps=1e-4"),
    method("sign-only", "sign-only"),
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
            method("tmin", "tmin:tmin-eps={x}"),
            method("offset-normal", "offset-normal:offset-normal-eps={x}"),
            method("offset-direction", "offset-direction:offset-direction-eps={x}"),
            method("validity-bit all, fixed", "validity-bit:vb-policy=all:vb-eps-mode=fixed:vb-eps={x}"),
            method("validity-bit vote, fixed", "validity-bit:vb-policy=vote:vb-eps-mode=fixed:vb-eps={x}"),
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
            method("validity-bit all", "validity-bit:vb-policy=all:vb-min-exponent=1:vb-guard-bits={x}"),
            method("validity-bit vote", "validity-bit:vb-policy=vote:vb-min-exponent=1:vb-guard-bits={x}"),
            method("validity-bit vote, normal test only", "validity-bit:vb-policy=vote:vb-tests=normal:vb-min-exponent=1:vb-guard-bits={x}"),
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
            method("offset-adaptive", "offset-adaptive:adaptive-int-scale={x}"),
            method("offset-adaptive+primid", "offset-adaptive+primid:adaptive-int-scale={x}"),
        ],
    },
    {
        "name": "distance", "scenario": "random-triangles", "rays": 200, "seed": 1,
        "title": "Distance from the origin (Ray Tracing Gems Figure 6-7 triangles)",
        "about": "Isolated random triangles (edge scale 2^-16 to 2^22) whose centres lie "
                 "2^k from the origin; a bounce and diffuse children leave each hit. Every "
                 "child's exact answer is a miss, so every hit is a self hit.",
        "key": "dist_min_log2", "set": {}, "values": list(range(-16, 25, 4)),
        "pair": "dist_max_log2", "xlog": False, "hard": "high",
        "xlabel": "log2 of the distance from the origin", "unit": "",
        "methods": DEFAULT_METHODS,
    },
    {
        "name": "triangle-size", "scenario": "random-triangles", "rays": 200, "seed": 1,
        "title": "Triangle size (Ray Tracing Gems Figure 6-7 triangles)",
        "about": "Isolated random triangles at distances 2^-16 to 2^22 whose vertices lie "
                 "2^k from their centre.",
        "key": "size_min_log2", "set": {}, "values": list(range(-16, 23, 4)),
        "pair": "size_max_log2", "xlog": False, "hard": "low",
        "xlabel": "log2 of the triangle size", "unit": "",
        "methods": DEFAULT_METHODS,
    },
    {
        "name": "far-instance", "scenario": "far-instance", "rays": 150, "seed": 1,
        "title": "A mesh 2^k from the origin (bunny paths under a float32 instance transform)",
        "about": "The bunny translated by 2^k along (1, 1, 1); multi-bounce paths over it.",
        "key": "k", "values": list(range(0, 25, 4)), "xlog": False, "hard": "high",
        "xlabel": "k (translation 2^k)", "unit": "",
        "methods": DEFAULT_METHODS,
    },
    {
        "name": "grazing-angle", "scenario": "grazing", "rays": 300, "seed": 1,
        "title": "Grazing angle of the child ray (plane, cylinder, bowl)",
        "about": "Diffuse children leaving a tessellated plane, a convex cylinder and a "
                 "concave bowl at one fixed elevation angle per point.",
        "key": "angle_min", "pair": "angle_max", "set": {"angles": 1},
        "values": [1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.0524, 0.1745], "xlog": True, "hard": "low",
        "xlabel": "elevation of the child above the surface (rad)", "unit": "rad",
        "methods": DEFAULT_METHODS,
    },
    {
        "name": "dihedral-angle", "scenario": "shared-edges", "rays": 300, "seed": 1,
        "title": "Dihedral angle at shared edges (flat, convex, concave sheets)",
        "about": "Spawn points a few ulps from shared edges and vertices of sheets folded "
                 "by 180 +/- delta degrees; grazing children.",
        "key": "delta", "values": [0, 0.001, 0.01, 0.1, 0.3, 1], "symlog": 0.001, "hard": "both",
        "xlabel": "fold delta (degrees from flat)", "unit": "deg",
        "methods": DEFAULT_METHODS,
    },
    {
        "name": "crevice-angle", "scenario": "crevice", "rays": 300, "seed": 1,
        "title": "Opening angle of a crevice (Ray Tracing Gems Figure 6-8)",
        "about": "Concave wedges; spawn points 1e-6 to 1e-2 from the crease.",
        "key": "angles", "values": [1, 2, 5, 10, 20, 45, 90], "xlog": True, "hard": "low",
        "xlabel": "opening angle (degrees)", "unit": "deg",
        "methods": DEFAULT_METHODS,
    },
    {
        "name": "layer-separation", "scenario": "layers", "rays": 300, "seed": 1,
        "title": "Separation of parallel layers, in units of the offset (1e-4)",
        "about": "A decal over a wall and a thin sheet, S times 1e-4 apart; refraction, "
                 "reflection and shadow children toward the neighbour. Fixed offsets and "
                 "tmin are 1e-4.",
        "key": "separation", "traces": "layers-sep*.jsonl",
        "values": [0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0], "xlog": True, "hard": "low",
        "xlabel": "separation / offset", "unit": "x offset",
        "methods": DEFAULT_METHODS,
    },
]
