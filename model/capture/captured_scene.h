// CapturedScene: one committed Embree scene as the capture shim saw it,
// read from its snapshot file, with the trace's triangle numbering: the
// captured triangle and quad geometries in ascending geomID, primitives in
// order, so that triangle id = first_triangle(geomID) + primID, and for quads
// first_triangle(geomID) + 2 primID for (v0, v1, v3) and + 1 for (v2, v3, v1),
// the two triangles Embree splits a quad into.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "capture/raw_capture_format.h"
#include "datapath/triangle.h"

namespace vbsim::capture {

struct CapturedGeometry {
  uint32_t geom_id = 0;
  uint32_t type = 0;  ///< RTCGeometryType
  RawGeometryStatus status = RawGeometryStatus::Captured;
  int64_t first_triangle = -1;  ///< trace id of primitive 0 (captured geometries only)
  uint32_t triangles = 0;        ///< trace triangles (two per quad)
  uint32_t vertices = 0;
  uint32_t filters = 0;  ///< RawGeometryFilter bits: filter functions the application set
  uint32_t mask = 0xffffffffu;  ///< rtcSetGeometryMask: a ray sees the geometry when its mask shares a bit
};

/// A hit as the trace names it: its triangle (-1: not in the trace) and the
/// barycentrics on it, p = (1-u-v) v0 + u v1 + v v2.
struct TriangleHit {
  int64_t triangle = -1;
  float u = 0.0f, v = 0.0f;
};

/// The snapshot file of (scene ordinal, commit) of the same process; empty when there is none.
using SnapshotFinder = std::function<std::string(uint32_t scene, uint32_t commit)>;

class CapturedScene {
 public:
  /// Reads a snapshot file (scene-<pid>-<s>-<c>.bin). Throws std::runtime_error
  /// naming the file on a bad magic, a truncated file, or an index that points
  /// past its geometry's vertex buffer. An instance is flattened: the
  /// triangles of the scene it instances (read through `find`), each vertex
  /// transformed in double and rounded once to float32, take its place in the
  /// numbering. An instance of a scene that itself holds instances is not
  /// (NestedInstance: Embree reports only the outer instance of a hit here).
  static CapturedScene read(const std::string& path, const SnapshotFinder& find = {});

  /// Embree's hit (geomID, primID, u, v) as the trace names it; triangle -1
  /// when that geometry was not captured (or the primitive is out of range).
  /// A quad hit lies in its first triangle when u + v <= 1 (Embree's own
  /// split; on the diagonal both triangles hold the point), else in the
  /// second, whose barycentrics are 1 - u, 1 - v.
  TriangleHit triangle_hit(uint32_t geom_id, uint32_t prim_id, float u, float v) const;
  /// The hit of an intersect record (inside an instance: on the instance's
  /// flattened triangles); triangle -1 for a miss, an occlusion query, or a
  /// hit on geometry not captured.
  TriangleHit triangle_hit(const RawRay& r) const;
  /// Whether any instance was flattened into the scene.
  bool has_instances() const { return has_instances_; }

  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// Triangle k's ray-mask bits at [k]: its geometry's mask (rtcSetGeometryMask,
  /// all bits by default); inside an instance, the instance's mask where the
  /// instanced geometry keeps all bits, else the geometry's.
  const std::vector<uint32_t>& triangle_masks() const { return triangle_masks_; }
  /// (instance mask, geometry mask) pairs, both other than all bits and
  /// different, that one mask per triangle cannot hold: Embree needs a ray to
  /// share a bit with both, triangle_masks() holds the geometry's.
  const std::vector<std::pair<uint32_t, uint32_t>>& unheld_masks() const { return unheld_masks_; }
  const std::vector<CapturedGeometry>& geometries() const { return geometries_; }
  uint32_t scene() const { return scene_; }
  uint32_t commit() const { return commit_; }

 private:
  uint32_t scene_ = 0, commit_ = 0;
  std::vector<CapturedGeometry> geometries_;  ///< every attached geometry, ascending geomID
  std::vector<int64_t> first_by_geom_;        ///< geomID -> first triangle, -1 when not captured
  std::vector<uint32_t> count_by_geom_;       ///< geomID -> its primitives (triangles or quads)
  std::vector<bool> quads_by_geom_;           ///< geomID -> a quad geometry
  std::vector<std::shared_ptr<const CapturedScene>> instanced_by_geom_;  ///< geomID -> the scene an instance flattens
  bool has_instances_ = false;
  std::vector<Triangle> triangles_;
  std::vector<uint32_t> triangle_masks_;  ///< one per triangle
  std::vector<std::pair<uint32_t, uint32_t>> unheld_masks_;
};

/// Name of an RTCGeometryType value ("triangle", "quad", "instance", ...).
const char* embree_geometry_type_name(uint32_t type);
/// Why a geometry is not in the scene ("not triangles", "motion blur", ...).
const char* raw_geometry_status_name(RawGeometryStatus status);
/// "geomID 1 (instance: not triangles), geomID 3 (triangle: disabled)": every
/// geometry whose status is not `captured` (all of them when `all`).
std::string describe_geometries(const std::vector<CapturedGeometry>& geometries, bool all);

}  // namespace vbsim::capture
