// TraceRay and TraceHeader: one ray of a vbsim trace and the trace's header,
// field for field as ../docs/trace-format.md (the public contract) defines them.
// Optional fields carry a has_* flag so that a round trip keeps absent fields absent.
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "datapath/ray.h"
#include "datapath/vec3.h"

namespace vbsim {

/// A ray or triangle mask with every bit set: the default of both (a ray sees
/// a triangle when their masks share a bit, as Embree's ray masks decide).
constexpr uint32_t kAllMaskBits = 0xffffffffu;

/// Triangles [first, first + count) carry `mask` (the header's `triangle_masks`).
struct TriangleMaskRange {
  uint32_t first = 0;
  uint32_t count = 0;
  uint32_t mask = kAllMaskBits;
};

struct TraceHeader {
  int version = 1;
  std::string scene;        ///< path relative to the trace file, as written
  std::string scene_path;   ///< resolved path (directory of the trace file + scene)
  std::optional<Vec3f> light;
  std::string generator;    ///< empty when absent
  std::string description;  ///< empty when absent
  std::optional<std::array<float, 16>> transform;  ///< row-major 4x4, float32
  /// What wrote the file (version, command line, input checksums) as one
  /// compact JSON object; empty when absent. Optional, descriptive only.
  std::string provenance;
  /// What gave the rays' `reference` answers (e.g. the capturing renderer's
  /// Embree); empty when the rays carry none. In the binary form it selects
  /// the layout that holds them (docs/trace-binary.md).
  std::string reference;
  /// Ray masks (docs/trace-format.md): present when the trace's rays may carry
  /// a `mask`; each range gives triangles a mask other than all bits (empty:
  /// every triangle has all bits). In the binary form it selects layout 3.
  std::optional<std::vector<TriangleMaskRange>> triangle_masks;
};

/// TraceRay::reference_prim of an occlusion query its renderer found occluded
/// (by a triangle it does not name).
constexpr int32_t kReferenceOccluded = -2;

struct TraceRay {
  int64_t id = 0;
  int64_t parent = -1;
  RayKind kind = RayKind::Primary;
  Vec3f o;
  Vec3f d;
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();  ///< null in the text form
  int32_t parent_prim = -1;
  bool has_parent_t = false;
  float parent_t = 0.0f;
  bool has_parent_uv = false;
  float parent_u = 0.0f, parent_v = 0.0f;
  bool has_parent_ns = false;
  Vec3f parent_ns;

  /// Records where the parent ray hit: triangle `prim` at distance `t`, barycentrics (u, v).
  void set_parent_hit(int32_t prim, float t, float u, float v) {
    parent_prim = prim;
    has_parent_t = true;
    parent_t = t;
    has_parent_uv = true;
    parent_u = u;
    parent_v = v;
  }
  int8_t sign = -1;  ///< 0 or 1 when given, -1 when absent (computed from the scene)
  bool has_expect = false;
  int32_t expect_prim = -1;  ///< -1: the exact answer is a miss
  bool has_expect_t = false;
  double expect_t = 0.0;     ///< exact hit distance rounded to double
  /// IncompleteReason bits (trace/incomplete_reasons.h): why the renderer's
  /// answer for this ray depends on what the trace does not hold; 0 = none.
  uint32_t incomplete = 0;
  /// The answer the renderer's own tester gave (the header's `reference`):
  /// a triangle, -1 for none (a miss, or not occluded), kReferenceOccluded.
  bool has_reference = false;
  int32_t reference_prim = -1;
  bool has_reference_t = false;  ///< with a triangle: its hit distance
  float reference_t = 0.0f;
  /// The ray's mask: it sees only triangles whose mask shares a bit with it
  /// (only when the header declares `triangle_masks`; else all bits).
  uint32_t mask = kAllMaskBits;
};

}  // namespace vbsim
