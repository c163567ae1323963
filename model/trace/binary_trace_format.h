// The binary trace form (.vbt), version 1: a streamed, lossless, little-endian
// twin of the text form that numpy reads with one dtype. Layout (see
// docs/trace-binary.md for the full description and the numpy dtype):
//
//   offset 0   8 bytes  magic "VBSIMTRB"
//   offset 8   u32      layout version (1)
//   offset 12  u32      n = byte length of the header JSON
//   offset 16  n bytes  header JSON (the same object as a text trace's first
//                       line), then spaces up to a multiple of 8 bytes
//   then       96-byte records, one per ray, up to the end of the file
#pragma once
#include <cstddef>
#include <cstdint>

#include "trace/trace_error.h"
#include "trace/trace_record.h"

namespace vbsim {

constexpr char kBinaryTraceMagic[8] = {'V', 'B', 'S', 'I', 'M', 'T', 'R', 'B'};
constexpr uint32_t kBinaryTraceLayoutVersion = 1;
/// Layout 2: version 1's record followed by the reference answer (written
/// when the header names a `reference`).
constexpr uint32_t kBinaryTraceReferenceLayoutVersion = 2;
constexpr std::size_t kBinaryTraceReferenceRecordBytes = 104;
/// Layout 3: layout 2's record followed by the ray's mask and 4 reserved
/// bytes (written when the header declares `triangle_masks`).
constexpr uint32_t kBinaryTraceMaskLayoutVersion = 3;
constexpr std::size_t kBinaryTraceMaskRecordBytes = 112;
constexpr std::size_t kBinaryTracePreambleBytes = 16;  ///< magic + version + header length
constexpr std::size_t kBinaryTraceRecordBytes = 96;
constexpr uint32_t kBinaryTraceMaxHeaderBytes = 1u << 24;  ///< readers reject longer headers

/// Byte offset of each field in a record; all little-endian, naturally aligned.
namespace binary_trace_offset {
constexpr std::size_t id = 0;            ///< i64
constexpr std::size_t parent = 8;        ///< i64, -1 = none
constexpr std::size_t o = 16;            ///< 3 x f32
constexpr std::size_t d = 28;            ///< 3 x f32
constexpr std::size_t tmin = 40;         ///< f32
constexpr std::size_t tmax = 44;         ///< f32, +inf where the text form has null
constexpr std::size_t parent_prim = 48;  ///< i32, -1 = none
constexpr std::size_t parent_t = 52;     ///< f32, valid with kHasParentT
constexpr std::size_t parent_uv = 56;    ///< 2 x f32, valid with kHasParentUv
constexpr std::size_t parent_ns = 64;    ///< 3 x f32, valid with kHasParentNs
constexpr std::size_t expect_prim = 76;  ///< i32, valid with kHasExpect (-1 = miss)
constexpr std::size_t expect_t = 80;     ///< f64, valid with kHasExpectT
constexpr std::size_t kind = 88;         ///< u8, RayKind (0 primary .. 4 shadow)
constexpr std::size_t sign = 89;         ///< u8, 0 or 1, valid with kHasSign
constexpr std::size_t flags = 90;        ///< u16, BinaryTraceFlag bits
constexpr std::size_t incomplete = 92;   ///< u32, IncompleteReason bits (0: none; was `reserved`)
}  // namespace binary_trace_offset

/// Which optional fields a record carries. A field whose bit is clear is
/// absent: writers store 0 there (-1 in expect_prim), readers ignore the bytes.
enum BinaryTraceFlag : uint16_t {
  kHasParentT = 1u << 0,
  kHasParentUv = 1u << 1,
  kHasParentNs = 1u << 2,
  kHasExpect = 1u << 3,
  kHasExpectT = 1u << 4,  ///< only together with kHasExpect
  kHasSign = 1u << 5,
  kHasReference = 1u << 6,   ///< layout 2 only
  kHasReferenceT = 1u << 7,  ///< layout 2 only, with kHasReference
};
constexpr uint16_t kBinaryTraceKnownFlags = 0x3f;
constexpr uint16_t kBinaryTraceReferenceKnownFlags = 0xff;
namespace binary_trace_offset {
constexpr std::size_t reference_prim = 96;  ///< layout 2: i32, valid with kHasReference
constexpr std::size_t reference_t = 100;    ///< layout 2: f32, valid with kHasReferenceT
constexpr std::size_t mask = 104;           ///< layout 3: u32, the ray's mask (all bits: none given)
constexpr std::size_t reserved = 108;       ///< layout 3: u32, 0
}  // namespace binary_trace_offset

/// Whether records of layout `version` hold the reference answer (2 and 3).
constexpr bool binary_layout_has_reference(uint32_t version) { return version >= kBinaryTraceReferenceLayoutVersion; }
/// Whether they hold the ray's mask (3).
constexpr bool binary_layout_has_mask(uint32_t version) { return version == kBinaryTraceMaskLayoutVersion; }

/// The layout a writer uses for `header`: 3 when it declares ray masks, 2
/// when it names a reference, else 1 (what every earlier writer wrote).
inline uint32_t binary_trace_layout_for(const TraceHeader& header) {
  if (header.triangle_masks) return kBinaryTraceMaskLayoutVersion;
  return header.reference.empty() ? kBinaryTraceLayoutVersion : kBinaryTraceReferenceLayoutVersion;
}

/// Record bytes of layout `version` (1, 2 or 3).
constexpr std::size_t binary_trace_record_bytes(uint32_t version) {
  return binary_layout_has_mask(version)        ? kBinaryTraceMaskRecordBytes
         : binary_layout_has_reference(version) ? kBinaryTraceReferenceRecordBytes
                                                : kBinaryTraceRecordBytes;
}

/// Bytes the header JSON occupies in the file: n rounded up to a multiple of 8.
constexpr std::size_t binary_trace_padded_header_bytes(std::size_t n) { return (n + 7) / 8 * 8; }

/// Writes the 16-byte preamble for a header JSON of `header_bytes` bytes.
void encode_binary_trace_preamble(uint32_t header_bytes, uint8_t* out, uint32_t version = kBinaryTraceLayoutVersion);

/// Writes `ray` as one record (binary_trace_record_bytes(version) bytes at
/// `out`); layout 1 cannot hold a reference answer, layouts 1 and 2 no ray
/// mask other than all bits (a TraceFieldProblem).
void encode_binary_trace_record(const TraceRay& ray, uint8_t* out, uint32_t version = kBinaryTraceLayoutVersion);

/// Reads one record of layout `version` into `out`. Rejects what the layout
/// itself forbids (unknown flag bits or incomplete bits, a sign byte other
/// than 0/1, expect.t without expect, reference.t without reference, reserved
/// bytes other than 0); the
/// format's ray rules are check_trace_ray's.
bool decode_binary_trace_record(const uint8_t* record, TraceRay& out, TraceFieldProblem& problem,
                                uint32_t version = kBinaryTraceLayoutVersion);

/// Little-endian loads used by the readers of the preamble and records.
uint32_t load_le_u32(const uint8_t* p);
float load_le_f32(const uint8_t* p);

}  // namespace vbsim
