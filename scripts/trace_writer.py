#!/usr/bin/python3
"""Write vbsim traces from Python, with numpy alone: the text form (.jsonl) and
the binary form (.vbt), chosen by the file name as vbsim chooses it. This file
stands alone: copy it next to a renderer's scripts and import it.

    from trace_writer import TraceWriter
    with TraceWriter("out.vbt", scene="bunny.obj") as w:
        w.ray(id=0, o=(0, 5, 20), d=(0, 0, -1))                      # a camera ray
        w.ray(id=1, parent=0, kind="shadow", o=p, d=light - p, tmax=1,
              parent_prim=12, parent_t=t, parent_uv=(u, v), sign=0)
        w.rays(records)      # many rays at once: a RECORD_DTYPE array (binary or text)

Fields, defaults and meanings are the trace format's (docs/trace-format.md);
every float is stored as float32 and written so that it reads back bit for
bit. The writer applies the format's per-ray rules and refuses a child whose
parent id is not below its own while ids ascend (a parent must precede its
children); an error names the file, the ray's line or record and the field.
The file appears under its name only when close() succeeds (the context
manager calls it): until then it is written as NAME.partial, and an exception
inside the `with` block removes it.
"""
import json
import math
import os

try:
    import numpy as np
except ImportError:
    raise ImportError("trace_writer needs numpy, which this Python does not have: install it (Debian: "
                      "apt-get install python3-numpy) or run the script with /usr/bin/python3") from None

# The binary form's layout (docs/trace-binary.md); scripts/read_binary_trace.py reads with these.
MAGIC = b"VBSIMTRB"
LAYOUT_VERSION = 1
PREAMBLE_BYTES = 16

# One record; must match binary_trace_format.h field for field.
RECORD_DTYPE = np.dtype([
    ("id", "<i8"),
    ("parent", "<i8"),           # -1: camera ray
    ("o", "<f4", (3,)),
    ("d", "<f4", (3,)),
    ("tmin", "<f4"),
    ("tmax", "<f4"),             # +inf where the text form has null
    ("parent_prim", "<i4"),      # -1: none
    ("parent_t", "<f4"),         # valid when flags & HAS_PARENT_T
    ("parent_uv", "<f4", (2,)),  # valid when flags & HAS_PARENT_UV
    ("parent_ns", "<f4", (3,)),  # valid when flags & HAS_PARENT_NS
    ("expect_prim", "<i4"),      # valid when flags & HAS_EXPECT; -1: a miss
    ("expect_t", "<f8"),         # valid when flags & HAS_EXPECT_T
    ("kind", "u1"),              # index into KIND_NAMES
    ("sign", "u1"),              # 0 or 1, valid when flags & HAS_SIGN
    ("flags", "<u2"),
    ("incomplete", "<u4"),       # INCOMPLETE_REASONS bits, 0: none (docs/trace-binary.md)
])
assert RECORD_DTYPE.itemsize == 96
# Layout 2 (a header with a "reference"): the same record, then the renderer's own answer.
REFERENCE_LAYOUT_VERSION = 2
REFERENCE_RECORD_DTYPE = np.dtype(RECORD_DTYPE.descr + [
    ("reference_prim", "<i4"),   # valid when flags & HAS_REFERENCE; -1: none, -2: occluded
    ("reference_t", "<f4"),      # valid when flags & HAS_REFERENCE_T
])
assert REFERENCE_RECORD_DTYPE.itemsize == 104
# Layout 3 (a header with "triangle_masks"): layout 2's record, then the ray's mask.
MASK_LAYOUT_VERSION = 3
MASK_RECORD_DTYPE = np.dtype(REFERENCE_RECORD_DTYPE.descr + [
    ("mask", "<u4"),             # the ray's mask; 0xffffffff (all bits) when the text form has none
    ("reserved", "<u4"),         # 0
])
assert MASK_RECORD_DTYPE.itemsize == 112
HAS_REFERENCE = 1 << 6
HAS_REFERENCE_T = 1 << 7

HAS_PARENT_T = 1 << 0
HAS_PARENT_UV = 1 << 1
HAS_PARENT_NS = 1 << 2
HAS_EXPECT = 1 << 3
HAS_EXPECT_T = 1 << 4
HAS_SIGN = 1 << 5

KIND_NAMES = ("primary", "reflect", "refract", "diffuse", "shadow")
# The `incomplete` field's reasons: bit k is INCOMPLETE_REASONS[k] (docs/trace-format.md).
INCOMPLETE_REASONS = ("instance", "quad", "grid", "subdivision", "curve", "point", "user", "motion_blur",
                      "other_geometry", "filter", "mask", "unlinked")

BINARY_EXTENSION = ".vbt"
_CHUNK = 4096  # records buffered before a write


class TraceWriteError(ValueError):
    """A ray or header the format does not allow, or a failed write; names file, place and field."""


def format_float32(x):
    """The shortest decimal that reads back to the float32 `x`, whichever way a
    reader rounds (docs/trace-binary.md, "Number fidelity")."""
    v = np.float32(x)
    if v == 0 and np.signbit(v):
        return "-0.0"  # "-0" would be the integer 0
    text = np.format_float_positional(v, unique=True, trim="-") if 1e-4 <= abs(v) < 1e16 or v == 0 \
        else np.format_float_scientific(v, unique=True, trim="-")
    if np.float32(float(text)) != v:  # the one float32 tie: write the exact double instead
        text = repr(float(v))
    return text


def _format_double(x):
    return "-0.0" if x == 0 and math.copysign(1, x) < 0 else repr(float(x))


def _float_list(values):
    return "[" + ",".join(format_float32(x) for x in values) + "]"


def _vec(values, n, name, fail):
    a = np.asarray(values, dtype=np.float64).reshape(-1)
    if a.size != n:
        fail(name, f"expected {n} numbers, got {a.size}")
    with np.errstate(over="ignore", invalid="ignore"):  # overflow to inf is refused below, by name
        f = a.astype(np.float32)
    if not np.all(np.isfinite(f)):
        fail(name, f"{a.tolist()} is not finite (in float32)")
    return f


class TraceWriter:
    """Streams rays to `path`; binary when it ends in .vbt, text otherwise."""

    def __init__(self, path, scene, light=None, generator=None, description=None, transform=None):
        self.path = str(path)
        self.binary = self.path.endswith(BINARY_EXTENSION)
        self._partial = self.path + ".partial"
        self._count = 0
        self._last_id = None
        self._ascending = True
        self._dense = None  # (begin, end): every id in [begin, end) was written
        self._sparse = set()  # written ids outside that run
        self._buffer = np.zeros(_CHUNK, dtype=RECORD_DTYPE)
        self._buffered = 0
        if not str(scene):
            self._fail_header("scene", "is empty")
        # The header object as vbsim writes it: keys in format order, float32 numbers shortest.
        parts = ['"format":"vbsim-trace"', '"version":1', '"scene":' + json.dumps(str(scene), ensure_ascii=False)]
        if light is not None:
            parts.append('"light":' + _float_list(_vec(light, 3, "light", self._fail_header)))
        if generator:
            parts.append('"generator":' + json.dumps(str(generator), ensure_ascii=False))
        if description:
            parts.append('"description":' + json.dumps(str(description), ensure_ascii=False))
        if transform is not None:
            parts.append('"transform":' + _float_list(_vec(transform, 16, "transform", self._fail_header)))
        text = ("{" + ",".join(parts) + "}").encode("utf-8")
        self._file = open(self._partial, "wb")
        if self.binary:
            padded = (len(text) + 7) // 8 * 8
            self._file.write(MAGIC + np.array([LAYOUT_VERSION, len(text)], dtype="<u4").tobytes() +
                             text + b" " * (padded - len(text)))
        else:
            self._file.write(text + b"\n")

    # --- errors -------------------------------------------------------------------------------
    def _place(self):
        return f"record {self._count}" if self.binary else f"line {self._count + 2}"

    def _fail(self, field, message):
        raise TraceWriteError(f"{self.path}: {self._place()}: field '{field}': {message}")

    def _fail_header(self, field, message):
        raise TraceWriteError(f"{self.path}: header: field '{field}': {message}")

    # --- one ray --------------------------------------------------------------------------------
    def ray(self, id, o, d, parent=-1, kind="primary", tmin=0.0, tmax=math.inf, parent_prim=-1,
            parent_t=None, parent_uv=None, parent_ns=None, sign=None, expect=None, incomplete=()):
        """Appends one ray. `expect` is None or (prim, t) with t None for a miss; `incomplete` the
        names of the reasons the renderer's answer depends on what the trace does not hold."""
        # Values beyond float32 become inf here and are refused by the rules below with the
        # field's name, so numpy's own overflow warning would only come first and say less.
        with np.errstate(over="ignore", invalid="ignore"):
            self._ray(id, o, d, parent, kind, tmin, tmax, parent_prim, parent_t, parent_uv, parent_ns, sign,
                      expect, incomplete)

    def _ray(self, id, o, d, parent, kind, tmin, tmax, parent_prim, parent_t, parent_uv, parent_ns, sign, expect,
             incomplete):
        rec = np.zeros((), dtype=RECORD_DTYPE)
        rec["id"], rec["parent"], rec["parent_prim"], rec["expect_prim"] = int(id), int(parent), int(parent_prim), -1
        if kind not in KIND_NAMES:
            self._fail("kind", f"unknown kind {kind!r} (expected one of {', '.join(KIND_NAMES)})")
        rec["kind"] = KIND_NAMES.index(kind)
        rec["o"] = _vec(o, 3, "o", self._fail)
        rec["d"] = _vec(d, 3, "d", self._fail)
        rec["tmin"] = np.float32(tmin)
        rec["tmax"] = np.float32(tmax)
        flags = 0
        if parent_t is not None:
            rec["parent_t"], flags = np.float32(parent_t), flags | HAS_PARENT_T
        if parent_uv is not None:
            rec["parent_uv"], flags = _vec(parent_uv, 2, "parent_uv", self._fail), flags | HAS_PARENT_UV
        if parent_ns is not None:
            rec["parent_ns"], flags = _vec(parent_ns, 3, "parent_ns", self._fail), flags | HAS_PARENT_NS
        if sign is not None:
            if sign not in (0, 1):
                self._fail("sign", f"must be 0 or 1, got {sign!r}")
            rec["sign"], flags = int(sign), flags | HAS_SIGN
        if expect is not None:
            prim, t = expect
            rec["expect_prim"], flags = int(prim), flags | HAS_EXPECT
            if t is not None:
                rec["expect_t"], flags = float(t), flags | HAS_EXPECT_T
        rec["flags"] = flags
        bits = 0
        for name in incomplete:
            if name not in INCOMPLETE_REASONS:
                self._fail("incomplete", f"unknown reason {name!r} (expected one of {', '.join(INCOMPLETE_REASONS)})")
            bits |= 1 << INCOMPLETE_REASONS.index(name)
        rec["incomplete"] = bits
        self._append(rec.reshape(1))

    def rays(self, records):
        """Appends an array of RECORD_DTYPE records (absent fields by their flag bits, as in a .vbt)."""
        records = np.asarray(records, dtype=RECORD_DTYPE).reshape(-1)
        for start in range(0, len(records), _CHUNK):
            self._append(records[start:start + _CHUNK])

    # --- rules and output -----------------------------------------------------------------------
    def _check(self, r):
        """The format's per-ray rules (as vbsim's readers apply them), and parents before children."""
        flags, ident, parent = int(r["flags"]), int(r["id"]), int(r["parent"])
        if ident < 0:
            self._fail("id", f"{ident} is negative")
        if parent < -1:
            self._fail("parent", f"{parent} is below -1 (-1 means no parent)")
        if self._last_id is not None and ident <= self._last_id:
            self._ascending = False
        if parent == ident or (self._ascending and parent > ident):
            self._fail("parent", f"ray {ident} names parent {parent}, which cannot come before it; "
                                 "a parent must precede its children")
        if int(r["kind"]) >= len(KIND_NAMES):
            self._fail("kind", f"unknown kind {int(r['kind'])}")
        if parent >= 0 and int(r["kind"]) == 0:
            self._fail("kind", f"primary (the default), but the ray has parent {parent}: a camera ray has no "
                               "parent; give the child's kind (reflect, refract, diffuse or shadow)")
        if ident in self._sparse or (self._dense and self._dense[0] <= ident < self._dense[1]):
            self._fail("id", f"{ident} was given before: ids are unique within a trace")
        d = r["d"]
        if not (np.all(np.isfinite(r["o"]))):
            self._fail("o", "is not finite")
        if not np.all(np.isfinite(d)) or not np.any(d != 0):
            self._fail("d", "must be finite and non-zero")
        tmin, tmax = r["tmin"], r["tmax"]
        if not np.isfinite(tmin) or tmin < 0:
            self._fail("tmin", f"{float(tmin)} must be finite and >= 0")
        if np.isnan(tmax) or tmax < tmin:
            self._fail("tmax", f"{float(tmax)} must not be NaN or below tmin")
        if int(r["parent_prim"]) < -1:
            self._fail("parent_prim", "is below -1")
        for bit, name in ((HAS_PARENT_T, "parent_t"), (HAS_PARENT_UV, "parent_uv"), (HAS_PARENT_NS, "parent_ns")):
            if flags & bit and not np.all(np.isfinite(r[name])):
                self._fail(name, "is not finite")
        if flags & HAS_EXPECT_T:
            if not flags & HAS_EXPECT:
                self._fail("expect.t", "given without an expect answer")
            if int(r["expect_prim"]) == -1 or not math.isfinite(float(r["expect_t"])):
                self._fail("expect.t", "a hit distance needs a hit (prim >= 0) and must be finite")
        if flags & HAS_EXPECT and int(r["expect_prim"]) < -1:
            self._fail("expect.prim", "is below -1")
        if flags & ~0x3F or (flags & HAS_SIGN and int(r["sign"]) > 1):
            self._fail("flags", f"unknown flag bits or a sign other than 0 or 1 ({flags:#x})")
        if int(r["incomplete"]) >> len(INCOMPLETE_REASONS):
            self._fail("incomplete", f"unknown reason bits {int(r['incomplete']):#x}")
        self._last_id = ident
        self._remember(ident)

    def _remember(self, ident):
        if self._dense is None:
            self._dense = (ident, ident + 1)
        elif ident == self._dense[1]:
            end = ident + 1
            while end in self._sparse:
                self._sparse.remove(end)
                end += 1
            self._dense = (self._dense[0], end)
        else:
            self._sparse.add(ident)

    def _append(self, records):
        for r in records:
            self._check(r)
            self._count += 1
        if self.binary:
            clean = records.copy()
            flags = clean["flags"]
            clean["parent_t"][(flags & HAS_PARENT_T) == 0] = 0
            clean["parent_uv"][(flags & HAS_PARENT_UV) == 0] = 0
            clean["parent_ns"][(flags & HAS_PARENT_NS) == 0] = 0
            clean["expect_prim"][(flags & HAS_EXPECT) == 0] = -1
            clean["expect_t"][(flags & HAS_EXPECT_T) == 0] = 0
            clean["sign"][(flags & HAS_SIGN) == 0] = 0
            self._file.write(clean.tobytes())
        else:
            self._file.write("".join(self._json_line(r) for r in records).encode("utf-8"))

    @staticmethod
    def _json_line(r):
        """One ray as vbsim's text writer lays it out: fields in format order, defaults left out."""
        flags = int(r["flags"])
        vec = _float_list
        out = [f'"id":{int(r["id"])}']
        if int(r["parent"]) != -1:
            out.append(f'"parent":{int(r["parent"])}')
        if int(r["kind"]) != 0:
            out.append(f'"kind":"{KIND_NAMES[int(r["kind"])]}"')
        out += [f'"o":{vec(r["o"])}', f'"d":{vec(r["d"])}']
        if r["tmin"] != 0 or np.signbit(r["tmin"]):
            out.append(f'"tmin":{format_float32(r["tmin"])}')
        if not np.isposinf(r["tmax"]):
            out.append(f'"tmax":{format_float32(r["tmax"])}')
        if int(r["parent_prim"]) != -1:
            out.append(f'"parent_prim":{int(r["parent_prim"])}')
        if flags & HAS_PARENT_T:
            out.append(f'"parent_t":{format_float32(r["parent_t"])}')
        if flags & HAS_PARENT_UV:
            out.append(f'"parent_uv":{vec(r["parent_uv"])}')
        if flags & HAS_PARENT_NS:
            out.append(f'"parent_ns":{vec(r["parent_ns"])}')
        if flags & HAS_SIGN:
            out.append(f'"sign":{int(r["sign"])}')
        if flags & HAS_EXPECT:
            t = f',"t":{_format_double(float(r["expect_t"]))}' if flags & HAS_EXPECT_T else ""
            out.append(f'"expect":{{"prim":{int(r["expect_prim"])}{t}}}')
        bits = int(r["incomplete"])
        if bits:
            names = ",".join(f'"{n}"' for k, n in enumerate(INCOMPLETE_REASONS) if bits >> k & 1)
            out.append(f'"incomplete":[{names}]')
        return "{" + ",".join(out) + "}\n"

    def close(self):
        """Flushes and gives the file its name; returns the number of rays written."""
        if self._file is not None:
            self._file.close()
            self._file = None
            os.replace(self._partial, self.path)
        return self._count

    def abandon(self):
        """Closes and removes the partial file (an interrupted trace must not look complete)."""
        if self._file is not None:
            self._file.close()
            self._file = None
            os.remove(self._partial)

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        if exc_type is None:
            self.close()
        else:
            self.abandon()
        return False
