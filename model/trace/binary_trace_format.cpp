#include "trace/binary_trace_format.h"

#include <cstring>

#include <fmt/format.h>

#include "trace/incomplete_reasons.h"

namespace vbsim {

namespace off = binary_trace_offset;

namespace {

void store_u16(uint8_t* p, uint16_t v) {
  p[0] = static_cast<uint8_t>(v);
  p[1] = static_cast<uint8_t>(v >> 8);
}
void store_u32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
void store_u64(uint8_t* p, uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
void store_f32(uint8_t* p, float x) {
  uint32_t bits;
  std::memcpy(&bits, &x, 4);
  store_u32(p, bits);
}
void store_f64(uint8_t* p, double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, 8);
  store_u64(p, bits);
}
void store_vec3(uint8_t* p, Vec3f v) {
  store_f32(p, v.x);
  store_f32(p + 4, v.y);
  store_f32(p + 8, v.z);
}

uint16_t load_u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
uint64_t load_u64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
double load_f64(const uint8_t* p) {
  uint64_t bits = load_u64(p);
  double x;
  std::memcpy(&x, &bits, 8);
  return x;
}
Vec3f load_vec3(const uint8_t* p) { return {load_le_f32(p), load_le_f32(p + 4), load_le_f32(p + 8)}; }

bool fail(TraceFieldProblem& problem, const char* field, std::string message) {
  problem.field = field;
  problem.message = std::move(message);
  return false;
}

}  // namespace

uint32_t load_le_u32(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
         (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
}

float load_le_f32(const uint8_t* p) {
  uint32_t bits = load_le_u32(p);
  float x;
  std::memcpy(&x, &bits, 4);
  return x;
}

void encode_binary_trace_preamble(uint32_t header_bytes, uint8_t* out, uint32_t version) {
  std::memcpy(out, kBinaryTraceMagic, sizeof kBinaryTraceMagic);
  store_u32(out + 8, version);
  store_u32(out + 12, header_bytes);
}

void encode_binary_trace_record(const TraceRay& ray, uint8_t* out, uint32_t version) {
  std::memset(out, 0, binary_trace_record_bytes(version));
  uint16_t flags = 0;
  store_u64(out + off::id, static_cast<uint64_t>(ray.id));
  store_u64(out + off::parent, static_cast<uint64_t>(ray.parent));
  store_vec3(out + off::o, ray.o);
  store_vec3(out + off::d, ray.d);
  store_f32(out + off::tmin, ray.tmin);
  store_f32(out + off::tmax, ray.tmax);
  store_u32(out + off::parent_prim, static_cast<uint32_t>(ray.parent_prim));
  if (ray.has_parent_t) {
    flags |= kHasParentT;
    store_f32(out + off::parent_t, ray.parent_t);
  }
  if (ray.has_parent_uv) {
    flags |= kHasParentUv;
    store_f32(out + off::parent_uv, ray.parent_u);
    store_f32(out + off::parent_uv + 4, ray.parent_v);
  }
  if (ray.has_parent_ns) {
    flags |= kHasParentNs;
    store_vec3(out + off::parent_ns, ray.parent_ns);
  }
  store_u32(out + off::expect_prim, static_cast<uint32_t>(ray.has_expect ? ray.expect_prim : -1));
  if (ray.has_expect) flags |= kHasExpect;
  if (ray.has_expect_t) {
    flags |= kHasExpectT;
    store_f64(out + off::expect_t, ray.expect_t);
  }
  out[off::kind] = static_cast<uint8_t>(ray.kind);
  if (ray.sign != -1) {
    flags |= kHasSign;
    out[off::sign] = static_cast<uint8_t>(ray.sign);
  }
  if (binary_layout_has_mask(version)) {
    store_u32(out + off::mask, ray.mask);
    store_u32(out + off::reserved, 0);
  } else if (ray.mask != kAllMaskBits) {
    throw TraceFieldProblem{"mask", "the header declares no ray masks, so the layout has no room for one"};
  }
  if (binary_layout_has_reference(version)) {
    store_u32(out + off::reference_prim, static_cast<uint32_t>(ray.has_reference ? ray.reference_prim : -1));
    if (ray.has_reference) flags |= kHasReference;
    if (ray.has_reference_t) {
      flags |= kHasReferenceT;
      store_f32(out + off::reference_t, ray.reference_t);
    }
  } else if (ray.has_reference) {
    throw TraceFieldProblem{"reference", "the header names no reference, so the layout (1) has no room for it"};
  }
  store_u16(out + off::flags, flags);
  store_u32(out + off::incomplete, ray.incomplete);
}

bool decode_binary_trace_record(const uint8_t* in, TraceRay& out, TraceFieldProblem& problem, uint32_t version) {
  uint16_t flags = load_u16(in + off::flags);
  const uint16_t known =
      binary_layout_has_reference(version) ? kBinaryTraceReferenceKnownFlags : kBinaryTraceKnownFlags;
  if (flags & ~known) return fail(problem, "flags", fmt::format("unknown flag bits 0x{:04x}", flags & ~known));
  if ((flags & kHasReferenceT) && !(flags & kHasReference))
    return fail(problem, "reference.t", "flag has_reference_t set without has_reference");
  const uint32_t incomplete = load_le_u32(in + off::incomplete);
  if (incomplete & ~kIncompleteKnownBits)
    return fail(problem, "incomplete",
                fmt::format("unknown reason bits 0x{:x}", incomplete & ~kIncompleteKnownBits));
  if ((flags & kHasExpectT) && !(flags & kHasExpect))
    return fail(problem, "expect.t", "flag has_expect_t set without has_expect");
  if (binary_layout_has_mask(version) && load_le_u32(in + off::reserved) != 0)
    return fail(problem, "reserved", "bytes 108-111 of a layout 3 record must be 0");
  out = TraceRay{};
  out.id = static_cast<int64_t>(load_u64(in + off::id));
  out.parent = static_cast<int64_t>(load_u64(in + off::parent));
  out.kind = static_cast<RayKind>(in[off::kind]);
  out.o = load_vec3(in + off::o);
  out.d = load_vec3(in + off::d);
  out.tmin = load_le_f32(in + off::tmin);
  out.tmax = load_le_f32(in + off::tmax);
  out.parent_prim = static_cast<int32_t>(load_le_u32(in + off::parent_prim));
  if (flags & kHasParentT) {
    out.has_parent_t = true;
    out.parent_t = load_le_f32(in + off::parent_t);
  }
  if (flags & kHasParentUv) {
    out.has_parent_uv = true;
    out.parent_u = load_le_f32(in + off::parent_uv);
    out.parent_v = load_le_f32(in + off::parent_uv + 4);
  }
  if (flags & kHasParentNs) {
    out.has_parent_ns = true;
    out.parent_ns = load_vec3(in + off::parent_ns);
  }
  if (flags & kHasSign) {
    uint8_t sign = in[off::sign];
    if (sign > 1) return fail(problem, "sign", fmt::format("must be 0 or 1, got {}", sign));
    out.sign = static_cast<int8_t>(sign);
  }
  if (flags & kHasExpect) {
    out.has_expect = true;
    out.expect_prim = static_cast<int32_t>(load_le_u32(in + off::expect_prim));
  }
  if (flags & kHasExpectT) {
    out.has_expect_t = true;
    out.expect_t = load_f64(in + off::expect_t);
  }
  out.incomplete = incomplete;
  if (flags & kHasReference) {
    out.has_reference = true;
    out.reference_prim = static_cast<int32_t>(load_le_u32(in + off::reference_prim));
  }
  if (flags & kHasReferenceT) {
    out.has_reference_t = true;
    out.reference_t = load_le_f32(in + off::reference_t);
  }
  if (binary_layout_has_mask(version)) out.mask = load_le_u32(in + off::mask);
  return true;
}

}  // namespace vbsim
