#!/usr/bin/python3
"""Read a vbsim binary trace (.vbt) with numpy alone.

Layout (docs/trace-binary.md): 8-byte magic b"VBSIMTRB", u32 layout version
(1), u32 header-JSON length n, n bytes of header JSON padded with spaces to a
multiple of 8, then 96-byte little-endian records described by RECORD_DTYPE.

As a module:
    header, records = read_binary_trace("trace.vbt")      # whole file
    for chunk in iter_binary_trace("trace.vbt"): ...      # streamed, bounded memory
As a program:
    /usr/bin/python3 scripts/read_binary_trace.py trace.vbt [--head N]
"""
import argparse
import json
import os
import sys

import numpy as np

# The layout's constants live in trace_writer.py, a module that stands alone.
from trace_writer import (HAS_EXPECT, HAS_EXPECT_T, HAS_PARENT_NS, HAS_PARENT_T, HAS_PARENT_UV,  # noqa: F401
                          HAS_REFERENCE, HAS_REFERENCE_T, HAS_SIGN, INCOMPLETE_REASONS, KIND_NAMES,
                          LAYOUT_VERSION, MAGIC, PREAMBLE_BYTES, RECORD_DTYPE, REFERENCE_LAYOUT_VERSION,
                          REFERENCE_RECORD_DTYPE, MASK_LAYOUT_VERSION, MASK_RECORD_DTYPE)


class BinaryTraceError(ValueError):
    """A file that is not a well-formed binary trace; the message names the file."""


def record_dtype(path):
    """The records' dtype: RECORD_DTYPE, REFERENCE_RECORD_DTYPE for layout 2, MASK_RECORD_DTYPE for 3."""
    with open(path, "rb") as f:
        preamble = f.read(PREAMBLE_BYTES)
    version = int(np.frombuffer(preamble, dtype="<u4", count=1, offset=8)[0]) if len(preamble) == PREAMBLE_BYTES else 0
    return {REFERENCE_LAYOUT_VERSION: REFERENCE_RECORD_DTYPE, MASK_LAYOUT_VERSION: MASK_RECORD_DTYPE}.get(
        version, RECORD_DTYPE)


def read_header(path):
    """Returns (header dict, byte offset of the first record)."""
    with open(path, "rb") as f:
        preamble = f.read(PREAMBLE_BYTES)
        if preamble[:8] != MAGIC:
            raise BinaryTraceError(f"{path}: not a binary vbsim trace (no {MAGIC!r} magic)")
        if len(preamble) < PREAMBLE_BYTES:
            raise BinaryTraceError(f"{path}: truncated: the file ends inside its preamble")
        version, n = np.frombuffer(preamble, dtype="<u4", count=2, offset=8)
        if version not in (LAYOUT_VERSION, REFERENCE_LAYOUT_VERSION, MASK_LAYOUT_VERSION):
            raise BinaryTraceError(f"{path}: unsupported binary layout version {version}")
        padded = (int(n) + 7) // 8 * 8
        text = f.read(padded)
        if len(text) != padded:
            raise BinaryTraceError(f"{path}: header: truncated")
    if not text[:n].endswith(b"}"):
        raise BinaryTraceError(f"{path}: header: the header JSON does not end at its stated length {int(n)}")
    header = json.loads(text[:n].decode("utf-8"))
    if header.get("format") != "vbsim-trace" or header.get("version") != 1:
        raise BinaryTraceError(f"{path}: header: not a version 1 vbsim trace header")
    return header, PREAMBLE_BYTES + padded


def record_count(path, offset):
    """Number of records after `offset`; raises on a partial last record."""
    dtype = record_dtype(path)
    payload = os.path.getsize(path) - offset
    count, rest = divmod(payload, dtype.itemsize)
    if rest:
        raise BinaryTraceError(f"{path}: record {count}: truncated: the file ends {rest} bytes "
                               f"into this {dtype.itemsize}-byte record")
    return count


def read_binary_trace(path):
    """Returns (header dict, structured array of all records, in record_dtype(path))."""
    header, offset = read_header(path)
    count = record_count(path, offset)
    return header, np.fromfile(path, dtype=record_dtype(path), count=count, offset=offset)


def iter_binary_trace(path, chunk_records=1 << 16):
    """Yields the records in arrays of at most chunk_records, never the whole file."""
    _, offset = read_header(path)
    count = record_count(path, offset)
    dtype = record_dtype(path)
    with open(path, "rb") as f:
        f.seek(offset)
        for _ in range(0, count, chunk_records):
            yield np.frombuffer(f.read(chunk_records * dtype.itemsize), dtype=dtype)


def describe(record):
    """One record as a dict of the fields it carries (absent optional fields left out)."""
    flags = int(record["flags"])
    ray = {"id": int(record["id"]), "parent": int(record["parent"]),
           "kind": KIND_NAMES[record["kind"]] if record["kind"] < len(KIND_NAMES) else int(record["kind"]),
           "o": record["o"].tolist(), "d": record["d"].tolist(),
           "tmin": float(record["tmin"]),
           "tmax": None if np.isposinf(record["tmax"]) else float(record["tmax"]),
           "parent_prim": int(record["parent_prim"])}
    if flags & HAS_PARENT_T:
        ray["parent_t"] = float(record["parent_t"])
    if flags & HAS_PARENT_UV:
        ray["parent_uv"] = record["parent_uv"].tolist()
    if flags & HAS_PARENT_NS:
        ray["parent_ns"] = record["parent_ns"].tolist()
    if flags & HAS_SIGN:
        ray["sign"] = int(record["sign"])
    if "reference_prim" in record.dtype.names and flags & HAS_REFERENCE:
        prim = int(record["reference_prim"])
        ray["reference"] = {"occluded": True} if prim == -2 else {"prim": prim}
        if flags & HAS_REFERENCE_T:
            ray["reference"]["t"] = float(record["reference_t"])
    if "mask" in record.dtype.names and int(record["mask"]) != 0xFFFFFFFF:
        ray["mask"] = int(record["mask"])
    if int(record["incomplete"]):
        ray["incomplete"] = [n for k, n in enumerate(INCOMPLETE_REASONS) if int(record["incomplete"]) >> k & 1]
    if flags & HAS_EXPECT:
        ray["expect"] = {"prim": int(record["expect_prim"])}
        if flags & HAS_EXPECT_T:
            ray["expect"]["t"] = float(record["expect_t"])
    return ray


def main():
    parser = argparse.ArgumentParser(description="Summarise a vbsim binary trace (.vbt).")
    parser.add_argument("path")
    parser.add_argument("--head", type=int, default=0, help="print the first N records")
    args = parser.parse_args()
    try:
        header, records = read_binary_trace(args.path)
    except BinaryTraceError as e:
        print(e, file=sys.stderr)
        return 1
    print(json.dumps(header))
    kinds = np.bincount(records["kind"], minlength=len(KIND_NAMES))
    print(f"{len(records)} rays: " +
          ", ".join(f"{n} {name}" for name, n in zip(KIND_NAMES, kinds) if n))
    for record in records[:args.head]:
        print(json.dumps(describe(record)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
