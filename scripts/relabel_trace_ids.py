#!/usr/bin/python3
"""Writes a binary trace with the same rays in the same order and other ids (the
parents relabelled alike), to measure what ids out of order cost in memory
(docs/reliability.md, "Bounded memory"):

    /usr/bin/python3 scripts/relabel_trace_ids.py SOURCE.vbt MODE OUT.vbt

MODE: outlier-first  the first ray's id above every other (the rest in order)
      spread         id * 3 + 7 (ascending, with gaps)
      random         distinct random ids in [0, 2^62) (seed 1)
The header is SOURCE's as it is (write OUT beside SOURCE).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402

from read_binary_trace import RECORD_DTYPE, read_header  # noqa: E402


def new_ids(ids, mode):
    if mode == "outlier-first":
        out = ids.copy()
        out[0] = ids.max() + 1
        return out
    if mode == "spread":
        return ids * 3 + 7
    if mode == "random":
        rng = np.random.default_rng(1)
        labels = np.unique(rng.integers(0, 1 << 62, size=len(ids) + len(ids) // 8 + 16, dtype=np.int64))
        rng.shuffle(labels)
        return labels[: len(ids)]
    sys.exit(f"relabel_trace_ids: unknown mode '{mode}'\n" + __doc__)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    source, mode, out = sys.argv[1:]
    _, start = read_header(source)
    with open(source, "rb") as f:
        prefix = f.read(start)
        records = np.frombuffer(f.read(), dtype=RECORD_DTYPE).copy()
    ids = records["id"]
    if len(np.unique(ids)) != len(ids):
        sys.exit(f"relabel_trace_ids: {source} has duplicate ids")
    relabelled = new_ids(ids, mode)
    order = np.argsort(ids)
    has_parent = records["parent"] >= 0
    at = np.searchsorted(ids[order], records["parent"][has_parent])
    records["parent"][has_parent] = relabelled[order][at]
    records["id"] = relabelled
    tmp = out + ".partial"
    with open(tmp, "wb") as f:
        f.write(prefix)
        f.write(records.tobytes())
    os.replace(tmp, out)
    print(f"relabel_trace_ids: {len(records)} rays, ids {mode} -> {out}")


if __name__ == "__main__":
    main()
