// Scene: the triangles of one scene file, numbered as the trace spec says
// (from 0, meshes in file order, faces in file order, polygons triangulated),
// with optional per-vertex shading normals and an optional float32 transform.
#pragma once
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "datapath/triangle.h"

namespace vbsim {

class WorkProgress;

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Largest |coordinate| of a scene vertex (after the trace's transform), 2^126
/// (about 8.5e37); every finite float32 up to it, denormals included, is
/// supported. Within it, the difference of two coordinates (a box's extent, a
/// triangle's edge, a vertex seen from a ray origin in the scene) is finite in
/// float32; beyond, a scene spanning both signs has extents of infinity, on
/// which Embree's BVH builder aborted (docs/scene.md).
constexpr float kMaxSceneCoordinate = 0x1p126f;

/// fminf and fmaxf as this C library computes them (the second argument when
/// both are equal, so fmin(+0, -0) is -0; the one that is a number when the
/// other is NaN; the first when both are), written out so that a box grows without
/// a library call a coordinate (scene_bounds_test.cpp holds them against the
/// library's).
inline float fmin_inline(float a, float b) {
  if (a < b) return a;
  if (b <= a) return b;
  return a != a && b == b ? b : a;  // unordered: the one that is a number, else the first
}
inline float fmax_inline(float a, float b) {
  if (a > b) return a;
  if (b >= a) return b;
  return a != a && b == b ? b : a;
}

struct Bounds3f {
  Vec3f lo{INFINITY, INFINITY, INFINITY};
  Vec3f hi{-INFINITY, -INFINITY, -INFINITY};
  /// Grows the box to hold `p`: lo = fmin(lo, p), hi = fmax(hi, p) per axis.
  void extend(Vec3f p) {
    lo = {fmin_inline(lo.x, p.x), fmin_inline(lo.y, p.y), fmin_inline(lo.z, p.z)};
    hi = {fmax_inline(hi.x, p.x), fmax_inline(hi.y, p.y), fmax_inline(hi.z, p.z)};
  }
};

struct Scene {
  std::string source;                           ///< file it was loaded from
  std::vector<Triangle> triangles;              ///< index = triangle id
  std::vector<std::array<Vec3f, 3>> normals;    ///< per-vertex shading normals, or empty
  Bounds3f bounds;
  /// Per-triangle ray-mask bits (a trace header's triangle_masks,
  /// scene/triangle_masks.h), or empty: every triangle has all bits.
  std::vector<uint32_t> triangle_masks;

  int32_t size() const { return static_cast<int32_t>(triangles.size()); }
  bool has_normals() const { return !normals.empty(); }
  /// The mask of triangle k at [k], or null when the scene has no masks.
  const uint32_t* mask_table() const { return triangle_masks.empty() ? nullptr : triangle_masks.data(); }
  /// Shading normal at barycentrics (u, v): (1-u-v) n0 + u n1 + v n2, unnormalised.
  /// Precondition: has_normals().
  Vec3f shading_normal(int32_t prim, float u, float v) const;
};

/// Loads a PLY or OBJ scene (docs/scene.md). `transform` (row-major 4x4) is applied to every
/// vertex in float32 before anything else; normals get its inverse transpose.
/// Throws SceneError naming the file on any failure (missing, unreadable, no triangles).
/// `progress`, when given, is told each step (reading, checking, reading
/// triangles) and how far it is (progress/work_progress.h).
Scene load_scene(const std::string& path,
                 const std::optional<std::array<float, 16>>& transform = std::nullopt,
                 WorkProgress* progress = nullptr);

/// Builds a scene directly from triangles (tests and generators).
Scene make_scene(std::vector<Triangle> triangles,
                 std::vector<std::array<Vec3f, 3>> normals = {});

}  // namespace vbsim
