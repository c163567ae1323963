#!/usr/bin/python3
"""Writes the bundled Stanford bunny as an OBJ file with per-vertex normals.

Input: the index.js of the npm package `bunny` (public domain), which holds
`exports.positions=[[x,y,z],...]` and `exports.cells=[[a,b,c],...]` (0-based).
Output: `v` lines (the package's positions, see below), `vn` lines
(area-weighted vertex normals: the sum of the unnormalised face normals
(v1 - v0) x (v2 - v0) of the faces around a vertex, computed in double from
the float32 positions and normalised), and `f a//a b//b c//c` faces in the
package's order, so the OBJ's triangle k is the package's cell k.

Every number is first rounded to float32 (the precision vbsim computes in), then
written in fixed notation with the fewest decimals that both a correctly
rounding reader (strtof) and assimp's OBJ reader turn back into that float32.
assimp's reader is not correctly rounding: it adds the float32 integer part to
the fraction rounded to float32, and for |x| >= 1 that double rounding is off
by one ulp for 369 of the 5517 coordinates as the package writes them.
Writing reader-proof decimals keeps every program that loads the OBJ on
exactly the same triangles.

Usage: make_bunny_mesh.py PATH/TO/bunny/index.js OUTPUT.obj
Standard library only.
"""
import json
import math
import re
import struct
import sys
from fractions import Fraction

# assimp's fast_atof_table: 10^-i as double constants, i = 0..15.
ASSIMP_POWERS = [float("1e-%d" % i) for i in range(16)]
ASSIMP_RELEVANT_DECIMALS = 15


def read_package(index_js_path):
    """Returns (positions, cells) parsed from the package's index.js."""
    with open(index_js_path, encoding="utf-8") as f:
        text = f.read()
    arrays = {}
    for name in ("positions", "cells"):
        match = re.search(r"exports\.%s\s*=\s*(\[.*?\]\s*\])" % name, text, re.S)
        if match is None:
            sys.exit("%s: no exports.%s array" % (index_js_path, name))
        # Positions are kept as exact decimals (Fraction) so they round to float32 once.
        arrays[name] = json.loads(match.group(1), parse_float=Fraction, parse_int=int)
    positions, cells = arrays["positions"], arrays["cells"]
    for i, p in enumerate(positions):
        if len(p) != 3 or not all(isinstance(x, (int, Fraction)) for x in p):
            sys.exit("%s: positions[%d] is not 3 finite numbers" % (index_js_path, i))
    for i, c in enumerate(cells):
        if len(c) != 3 or not all(isinstance(k, int) and 0 <= k < len(positions) for k in c):
            sys.exit("%s: cells[%d] is not 3 vertex indices" % (index_js_path, i))
    return positions, cells


def round_f32(x):
    """Nearest float32 (ties to even) of the exact rational x, as a Python float."""
    x = Fraction(x)
    if x == 0:
        return 0.0
    exponent = math.floor(math.log2(abs(x)))
    while Fraction(2) ** exponent > abs(x):  # log2 of a Fraction may be off by one
        exponent -= 1
    while Fraction(2) ** (exponent + 1) <= abs(x):
        exponent += 1
    if exponent < -126 or exponent > 127:
        sys.exit("value %s is outside the normal float32 range" % x)
    scale = Fraction(2) ** (23 - exponent)
    return float(Fraction(round(x * scale)) / scale)  # round() on a Fraction ties to even


def f32_of_double(x):
    """static_cast<float>(double x): one IEEE rounding."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def assimp_parse(text):
    """The float32 assimp 5.2's OBJ reader (fast_atoreal_move<float>) makes of a
    fixed-notation decimal: float(integer part) + float(fraction computed in double)."""
    negative = text.startswith("-")
    integer, _, fraction = text.lstrip("+-").partition(".")
    value = round_f32(int(integer)) if integer else 0.0
    if fraction:
        digits = fraction[:ASSIMP_RELEVANT_DECIMALS]
        part = float(int(digits)) * ASSIMP_POWERS[len(digits)]
        value = round_f32(Fraction(value) + Fraction(f32_of_double(part)))
    return -value if negative else value


def reader_proof_decimal(value):
    """Fewest-decimals fixed-notation text that strtof and assimp both read as the
    float32 `value`."""
    for decimals in range(0, 60):
        text = "%.*f" % (decimals, value)
        # Trailing zeros are kept: assimp's result depends on the digit count.
        if round_f32(Fraction(text)) == value and assimp_parse(text) == value:
            return text
    sys.exit("no decimal reads back as %r in both readers" % value)


def vertex_normals(positions, cells):
    """Area-weighted, normalised per-vertex normals (double precision)."""
    sums = [[0.0, 0.0, 0.0] for _ in positions]
    for a, b, c in cells:
        p0, p1, p2 = (positions[k] for k in (a, b, c))
        e1 = [p1[i] - p0[i] for i in range(3)]
        e2 = [p2[i] - p0[i] for i in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1],
             e1[2] * e2[0] - e1[0] * e2[2],
             e1[0] * e2[1] - e1[1] * e2[0]]
        for k in (a, b, c):
            for i in range(3):
                sums[k][i] += n[i]
    normals = []
    for k, s in enumerate(sums):
        length = math.sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2])
        if length == 0.0:
            sys.exit("vertex %d has no well-defined normal (unused or only degenerate faces)" % k)
        normals.append([x / length for x in s])
    return normals


def write_obj(path, positions, normals, cells):
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("# Stanford bunny (Stanford 3D Scanning Repository), public domain,\n")
        f.write("# from the npm package 'bunny' 1.0.1; written by scripts/make_bunny_mesh.py.\n")
        f.write("# %d vertices, %d triangles; normals are area-weighted vertex normals.\n"
                % (len(positions), len(cells)))
        for p in positions:
            f.write("v %s %s %s\n" % tuple(reader_proof_decimal(x) for x in p))
        for n in normals:
            f.write("vn %s %s %s\n" % tuple(reader_proof_decimal(round_f32(x)) for x in n))
        for a, b, c in cells:
            f.write("f %d//%d %d//%d %d//%d\n" % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1))


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_bunny_mesh.py PATH/TO/bunny/index.js OUTPUT.obj")
    exact_positions, cells = read_package(sys.argv[1])
    positions = [[round_f32(x) for x in p] for p in exact_positions]
    # Normals from the float32 positions, the triangles every reader will see.
    write_obj(sys.argv[2], positions, vertex_normals(positions, cells), cells)
    print("%s: %d vertices, %d triangles" % (sys.argv[2], len(positions), len(cells)))


if __name__ == "__main__":
    main()
