#!/usr/bin/python3
"""The vbsim configuration that models rtcore-systemc's core with the given tb_top arguments.

    scripts/rtcore_config.py [LP_L1C_ENTRIES [HP_L1C_ENTRIES [IST_L1C_ENTRIES [T_TRAV_HIGH
                              [T_TRAV_LOW [NUM_LP [NUM_HP [NUM_IST]]]]]]]] > rtcore.json
    vbsim replay TRACE --mode cycle --config rtcore.json

The arguments are rtcore-systemc's `tb_top` arguments after its two file names, in its
order, with its defaults (512 512 512 0.5 0.47 4 4 1). The JSON printed is
`{"hw": {...}, "bvh": {"low_precision": {...}}}` on top of vbsim's `rtcore` preset
(model/hw/presets/rtcore.json) and its node marking (scene/bvh_precision.h);
docs/hw-model.md, "Modelling rtcore-systemc", says how each part maps and what the
mapping cannot express; those parts are also named on stderr.
"""
import json
import sys

# rtcore-systemc's src/misc/params.hpp: tb_top's defaults and the object sizes.
NAMES = ["LP_L1C_ENTRIES", "HP_L1C_ENTRIES", "IST_L1C_ENTRIES", "T_TRAV_HIGH", "T_TRAV_LOW",
         "NUM_LP", "NUM_HP", "NUM_IST"]
DEFAULTS = [512, 512, 512, 0.5, 0.47, 4, 4, 1]
KINDS = [int, int, int, float, float, int, int, int]
LP_BYTES, HP_BYTES, IST_BYTES = 40, 64, 36  # bytes of an object of the three caches (a node with one
                                             # low-precision child is 52 in rtcore; 64 here)
LP_LATENCY, IST_LATENCY = 20, 32             # box (both pools) and triangle latency, cycles
MANTISSA_BITS = 7                            # rtcore's low-precision bounds (params.hpp: mantissa_width)


class UsageError(Exception):
    pass


def parse(argv):
    """rtcore's argument list: the given values in order, the rest its defaults."""
    if len(argv) > len(NAMES):
        raise UsageError(f"at most {len(NAMES)} arguments ({' '.join(NAMES)}), got {len(argv)}")
    values = list(DEFAULTS)
    for i, text in enumerate(argv):
        try:
            values[i] = KINDS[i](text)
        except ValueError:
            raise UsageError(f"{NAMES[i]}: '{text}' is not a{'n integer' if KINDS[i] is int else ' number'}")
        if KINDS[i] is int and values[i] < (0 if i < 3 else 1):
            raise UsageError(f"{NAMES[i]}: must be at least {0 if i < 3 else 1}, got {values[i]}")
    return dict(zip(NAMES, values))


def config(a):
    """The hw object for rtcore's arguments `a` (a dict by NAMES)."""
    return {"hw": {
        "preset": "rtcore",
        # Two box pools: the full-precision one (NUM_HP) and the low-precision
        # one (NUM_LP), each unit holding an operation LP_LATENCY cycles.
        "box": {"count": a["NUM_HP"], "latency": LP_LATENCY, "issue_interval": LP_LATENCY},
        "box_low": {"count": a["NUM_LP"], "latency": LP_LATENCY, "issue_interval": LP_LATENCY},
        "triangle": {"count": a["NUM_IST"], "latency": IST_LATENCY, "issue_interval": IST_LATENCY},
        # The three object caches, each of its own entries and object size.
        "memory": {"objects": {"node_low": {"entries": a["LP_L1C_ENTRIES"], "bytes": LP_BYTES},
                               "node": {"entries": a["HP_L1C_ENTRIES"], "bytes": HP_BYTES},
                               "triangle": {"entries": a["IST_L1C_ENTRIES"], "bytes": IST_BYTES}}},
    },
        # rtcore's marking of nodes as low or high precision, by its two traversal costs.
        "bvh": {"low_precision": {"mantissa_bits": MANTISSA_BITS, "t_trav_high": a["T_TRAV_HIGH"],
                                  "t_trav_low": a["T_TRAV_LOW"], "narrow_arithmetic": True}}}


def not_modelled(a):
    """What of `a` the configuration cannot express."""
    return ["a node with one low-precision child: rtcore reads 52 bytes, vbsim's object caches 64",
            "rtcore's box and intersection controllers, arbiter and FIFOs: the preset's one controller's latency "
            "stands for their hops"]


def main(argv):
    try:
        a = parse(argv)
        out = config(a)
    except UsageError as e:
        print(f"rtcore_config.py: {e}", file=sys.stderr)
        print("\n".join(__doc__.strip().splitlines()[2:4]), file=sys.stderr)
        return 2
    for note in not_modelled(a):
        print(f"rtcore_config.py: not modelled: {note}", file=sys.stderr)
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
