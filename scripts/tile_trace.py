#!/usr/bin/python3
"""Writes a long binary trace by repeating one: the records of SOURCE.vbt,
COPIES times, the ids (and parent ids) of copy k shifted by k * (largest id + 1),
so that every copy is the same rays with the same parents and expectations.
The header is SOURCE's as it is (its scene path is relative to SOURCE's
directory: write OUT beside SOURCE). Used to measure that a replay's memory does not grow with trace length
(docs/reliability.md); streams the copies, holding one source in memory.

    /usr/bin/python3 scripts/tile_trace.py SOURCE.vbt COPIES OUT.vbt
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402

from read_binary_trace import RECORD_DTYPE, read_header  # noqa: E402


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    source, copies, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    _, start = read_header(source)
    with open(source, "rb") as f:
        prefix = f.read(start)
        records = np.frombuffer(f.read(), dtype=RECORD_DTYPE)
    step = int(records["id"].max()) + 1
    tmp = out + ".partial"
    with open(tmp, "wb") as f:
        f.write(prefix)
        for k in range(copies):
            block = records.copy()
            block["id"] += k * step
            has_parent = block["parent"] >= 0
            block["parent"][has_parent] += k * step
            f.write(block.tobytes())
    os.replace(tmp, out)
    print(f"tile_trace: {copies} x {len(records)} = {copies * len(records)} rays -> {out}")


if __name__ == "__main__":
    main()
