// CapturedScene: one committed Embree scene as the capture shim saw it,
// read from its snapshot file, with the trace's triangle numbering: the
// captured triangle geometries in ascending geomID, primitives in order, so
// that triangle id = first_triangle(geomID) + primID.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "capture/raw_capture_format.h"
#include "datapath/triangle.h"

namespace vbsim::capture {

struct CapturedGeometry {
  uint32_t geom_id = 0;
  uint32_t type = 0;  ///< RTCGeometryType
  RawGeometryStatus status = RawGeometryStatus::Captured;
  int64_t first_triangle = -1;  ///< trace id of primitive 0 (captured geometries only)
  uint32_t triangles = 0;
  uint32_t vertices = 0;
  uint32_t filters = 0;  ///< RawGeometryFilter bits: filter functions the application set
};

class CapturedScene {
 public:
  /// Reads a snapshot file (scene-<pid>-<s>-<c>.bin). Throws std::runtime_error
  /// naming the file on a bad magic, a truncated file, or an index that points
  /// past its geometry's vertex buffer.
  static CapturedScene read(const std::string& path);

  /// Trace triangle id of Embree's (geomID, primID), or -1 when that geometry
  /// was not captured (or the primitive is out of range).
  int64_t triangle_id(uint32_t geom_id, uint32_t prim_id) const;

  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<CapturedGeometry>& geometries() const { return geometries_; }
  uint32_t scene() const { return scene_; }
  uint32_t commit() const { return commit_; }

 private:
  uint32_t scene_ = 0, commit_ = 0;
  std::vector<CapturedGeometry> geometries_;  ///< every attached geometry, ascending geomID
  std::vector<int64_t> first_by_geom_;        ///< geomID -> first triangle, -1 when not captured
  std::vector<uint32_t> count_by_geom_;       ///< geomID -> its triangles
  std::vector<Triangle> triangles_;
};

/// Name of an RTCGeometryType value ("triangle", "quad", "instance", ...).
const char* embree_geometry_type_name(uint32_t type);
/// Why a geometry is not in the scene ("not triangles", "motion blur", ...).
const char* raw_geometry_status_name(RawGeometryStatus status);
/// "geomID 1 (instance: not triangles), geomID 3 (triangle: disabled)": every
/// geometry whose status is not `captured` (all of them when `all`).
std::string describe_geometries(const std::vector<CapturedGeometry>& geometries, bool all);

}  // namespace vbsim::capture
