"""The default architecture study of scripts/arch_sweep.py.

A definition (this one, or a JSON file given with --definition) has:
  trace     the sweep trace: {"scenario": S, "rays": N, "seed": K} (made by `vbsim gen`
            into the work folder) or {"file": PATH}
  sweeps    each: name, title, xlabel, chart (scaling, lines, cache, stalls, methods),
            x (a dotted `hw` field such as "memory.l1.size_bytes", or "method"),
            values, preset, series [{label, hw: {fields}, method}], optional xlog,
            group (sweeps of one group share a figure, named after the group)
  presets   optional: {"presets": [...], "traces": {label: trace}} for the preset table
  families  optional: {"rays": N, "seed": K, "max_traces": M, "methods": [...],
            "bundled": [PATH...], "preset": P, "scenarios": [...] (default: every
            scenario `vbsim scenarios` lists)} for build/results/method_cycles.json
Every point's configuration is {"hw": preset + series fields + the x field}.
"""

REAL = {"memory": {"ideal": False}}
IDEAL = {"memory": {"ideal": True}}

# Methods in `vbsim score` syntax; the validity-bit variants are spelled as in
# `vbsim score`'s default list so rows join with score tables by their label.
METHODS = [
    "none",
    "tmin",
    "primid",
    "offset-normal",
    "offset-adaptive",
    "offset-adaptive+primid",
    "offset-errbound",
    "validity-bit",
    "validity-bit:vb-policy=vote",
    "validity-bit:vb-eps-mode=fixed:vb-eps=1e-4",
    "validity-bit:vb-eps-mode=fixed:vb-eps=1e-4:vb-policy=vote",
    "sign-only",
    "reverse-shadow",
]

KIB = 1024

DEFAULT = {
    "trace": {"scenario": "paths", "rays": 5000, "seed": 1},
    "sweeps": [
        {"name": "scaling", "title": "Throughput scaling with cores (small preset, validity-bit)",
         "chart": "scaling", "x": "cores", "xlabel": "cores", "xlog": True, "preset": "small",
         "values": [1, 2, 4, 8, 16],
         "series": [{"label": "4 slots/core", "hw": {"slots_per_core": 4, **REAL}},
                    {"label": "16 slots/core", "hw": {"slots_per_core": 16, **REAL}},
                    {"label": "64 slots/core", "hw": {"slots_per_core": 64, **REAL}},
                    {"label": "64 slots/core, ideal memory", "hw": {"slots_per_core": 64, **IDEAL},
                     "bound": True}]},
        {"name": "slots", "title": "Ray slots per core (small preset: 4 cores)",
         "chart": "lines", "x": "slots_per_core", "xlabel": "ray slots per core", "xlog": True,
         "preset": "small", "values": [1, 2, 4, 8, 16, 32, 64, 128],
         "series": [{"label": "memory hierarchy", "hw": REAL},
                    {"label": "ideal memory", "hw": IDEAL, "bound": True}]},
        {"name": "box-latency", "group": "latencies", "title": "Box pipeline latency",
         "chart": "lines", "x": "box.latency", "xlabel": "box latency (cycles)", "xlog": True,
         "preset": "small", "values": [2, 4, 8, 16, 32], "series": "latency"},
        {"name": "triangle-latency", "group": "latencies", "title": "Triangle pipeline latency",
         "chart": "lines", "x": "triangle.latency", "xlabel": "triangle latency (cycles)", "xlog": True,
         "preset": "small", "values": [5, 10, 20, 40, 80], "series": "latency"},
        {"name": "avoidance-latency", "group": "latencies", "title": "Avoidance unit latency",
         "chart": "lines", "x": "avoidance.latency", "xlabel": "avoidance latency (cycles)", "xlog": True,
         "preset": "small", "values": [1, 3, 6, 12, 24, 48], "series": "latency"},
        {"name": "l1-size", "group": "caches", "title": "L1 size (per core)", "chart": "cache",
         "x": "memory.l1.size_bytes", "xlabel": "L1 size (KiB)", "xscale": KIB, "xlog": True,
         "preset": "small", "hit_rate": "l1_hit_rate",
         "values": [1 * KIB, 2 * KIB, 4 * KIB, 8 * KIB, 16 * KIB, 32 * KIB, 64 * KIB, 128 * KIB],
         "series": [{"label": "small preset", "hw": REAL}]},
        {"name": "l2-size", "group": "caches", "title": "L2 size (shared)", "chart": "cache",
         "x": "memory.l2.size_bytes", "xlabel": "L2 size (KiB)", "xscale": KIB, "xlog": True,
         "preset": "small", "hit_rate": "l2_hit_rate",
         "values": [16 * KIB, 32 * KIB, 64 * KIB, 128 * KIB, 256 * KIB, 512 * KIB, 1024 * KIB, 4096 * KIB],
         "series": [{"label": "small preset", "hw": REAL}]},
        {"name": "dram-latency", "group": "dram", "title": "DRAM latency", "chart": "stalls",
         "x": "memory.dram_latency", "xlabel": "DRAM latency (cycles)", "xlog": True, "preset": "small",
         "values": [30, 60, 120, 240, 480, 960], "series": "dram", "bars": "L2 32 KiB"},
        {"name": "dram-bandwidth", "group": "dram", "title": "DRAM bandwidth", "chart": "stalls",
         "x": "memory.dram_bytes_per_cycle", "xlabel": "DRAM bytes per cycle", "xlog": True,
         "preset": "small", "values": [1, 2, 4, 8, 16, 32, 64], "series": "dram", "bars": "L2 32 KiB"},
        {"name": "shading-latency", "group": "emission", "title": "Shading latency (dependencies on)",
         "chart": "lines", "x": "shader.latency_cycles", "xlabel": "shading latency (cycles)", "xlog": True,
         "preset": "small", "values": [1, 10, 50, 200, 800, 3200],
         "series": [{"label": "small preset", "hw": REAL},
                    {"label": "large preset", "hw": {"preset": "large", **REAL}}]},
        {"name": "emission-width", "group": "emission", "title": "Emission lanes (large preset)",
         "chart": "lines", "x": "source.rays_per_cycle", "xlabel": "rays emitted per cycle", "xlog": True,
         "preset": "large", "values": [1, 2, 4, 8],
         "series": [{"label": "ideal memory, independent rays",
                     "hw": {**IDEAL, "source": {"dependencies": False}}, "bound": True},
                    {"label": "ideal memory, dependencies", "hw": IDEAL},
                    {"label": "memory hierarchy, dependencies", "hw": REAL}]},
        {"name": "window", "group": "emission", "title": "Ray-emission window (dependencies on)",
         "chart": "lines", "x": "source.window", "xlabel": "window (rays)", "xlog": True,
         "preset": "large", "values": [64, 256, 1024, 4096, 16384],
         "series": [{"label": "large preset", "hw": REAL},
                    {"label": "large preset, ideal memory", "hw": IDEAL}]},
        {"name": "methods", "title": "Methods: cycles per ray and bits per ray in flight",
         "chart": "methods", "x": "method", "xlabel": "method", "preset": "small", "values": METHODS,
         "series": [{"label": "1 core x 1 slot", "hw": {"cores": 1, "slots_per_core": 1, **REAL}},
                    {"label": "small preset", "hw": REAL},
                    {"label": "large preset", "hw": {"preset": "large", **REAL}}]},
    ],
    # Named series lists shared by several sweeps.
    "series": {
        "latency": [{"label": "4 slots/core, ideal memory", "hw": {"slots_per_core": 4, **IDEAL}},
                    {"label": "32 slots/core, ideal memory", "hw": {"slots_per_core": 32, **IDEAL}},
                    {"label": "32 slots/core, memory hierarchy", "hw": {"slots_per_core": 32, **REAL}}],
        "dram": [{"label": "L2 1 MiB (preset)", "hw": REAL},
                 {"label": "L2 32 KiB", "hw": {"memory": {"ideal": False, "l2": {"size_bytes": 32 * KIB}}}}],
    },
    "method": "validity-bit",
    "presets": {"presets": ["small", "large"],
                "traces": {"bundled bunny (1008 rays)": {"file": "traces/bunny/paths.jsonl"},
                           "paths 5000 (sweep trace)": "sweep"}},
    "families": {"rays": 100, "seed": 1, "max_traces": 8, "methods": METHODS,
                 "bundled": ["traces/bunny/paths.jsonl"]},
}
