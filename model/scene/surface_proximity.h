// SurfaceProximity: whether a point lies within a distance of any triangle of
// a scene (Embree's point query over the triangles, the exact point-triangle
// distance computed in double). The capture uses it to tell a ray that starts
// on a surface (a secondary ray it could not link to a parent) from a camera
// ray, which must not be scored as one.
#pragma once
#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "datapath/vec3.h"
#include "scene/embree_device.h"
#include "scene/scene.h"

namespace vbsim {

/// Euclidean distance from `p` to the closed triangle `t` (double; 0 on it;
/// a degenerate triangle is treated as its edges).
double point_triangle_distance(const Vec3f& p, const Triangle& t);

class SurfaceProximity {
 public:
  /// Builds a point-query structure over `triangles` (copied).
  explicit SurfaceProximity(const std::vector<Triangle>& triangles);
  ~SurfaceProximity();
  SurfaceProximity(const SurfaceProximity&) = delete;
  SurfaceProximity& operator=(const SurfaceProximity&) = delete;

  /// Whether some triangle lies within `radius` (>= 0) of `p`; the nearest one's index in `*nearest`.
  bool within(const Vec3f& p, float radius, int64_t* nearest = nullptr) const;

 private:
  std::vector<Triangle> triangles_;
  std::unique_ptr<EmbreeDevice> device_;  // outlives scene_
  RTCScene scene_ = nullptr;
};

}  // namespace vbsim
