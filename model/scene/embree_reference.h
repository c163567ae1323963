// EmbreeReference: Embree's own closest-hit query over a Scene, the reference
// the project's BVH and testers are checked against and the baseline of the
// speed benchmark.
//
// Contract: one RTC_GEOMETRY_TYPE_TRIANGLE geometry whose primID is the scene's
// triangle id, built with RTC_SCENE_FLAG_ROBUST and RTC_BUILD_QUALITY_HIGH, in
// the acceleration structure Embree picks for the host (BVH8 of Triangle4v on
// one with AVX) unless the caller names another.
// Embree skips triangles it deems invalid (a vertex coordinate with magnitude
// above about 1.8e18, or non-finite); those are never reported.
#pragma once
#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "datapath/vec3.h"
#include "scene/embree_device.h"
#include "scene/scene.h"

namespace vbsim {

class EmbreeReference {
 public:
  /// Builds Embree's acceleration structure over `scene` (copied; the scene may
  /// be destroyed afterwards). Throws SceneError if Embree fails.
  /// `tri_accel`: Embree's name of the triangle acceleration structure to build
  /// (its tri_accel setting, e.g. "bvh4.triangle4v" for a 4-wide tree); empty:
  /// Embree's choice. A name Embree does not know is a SceneError, as is one
  /// with characters other than letters, digits, '.' and '_'.
  /// `exclusion`: also answer intersect_excluding (the scene is built
  /// to call an intersect context's filter function, at a small cost to every query).
  explicit EmbreeReference(const Scene& scene, const std::string& tri_accel = "", bool exclusion = false);
  ~EmbreeReference();
  EmbreeReference(const EmbreeReference&) = delete;
  EmbreeReference& operator=(const EmbreeReference&) = delete;

  /// Closest hit of the ray o + t d with t in [tnear, tfar] (rtcIntersect1, one
  /// ray on the calling thread). On a hit returns true and sets prim (triangle id),
  /// t (in units of d) and barycentrics u, v with p = (1-u-v) v0 + u v1 + v v2;
  /// on a miss returns false and leaves the outputs untouched. Thread-safe.
  bool intersect(Vec3f o, Vec3f d, float tnear, float tfar, int32_t& prim, float& t, float& u,
                 float& v) const;
  /// Whether any triangle meets o + t d with t in [tnear, tfar] (rtcOccluded1:
  /// Embree stops at the first it finds). Thread-safe.
  bool occluded(Vec3f o, Vec3f d, float tnear, float tfar) const;

  /// The same closest-hit query with triangle `exclude` never hit (a
  /// renderer's primitive-ID exclusion, as a filter function that rejects it);
  /// -1 excludes nothing. The same filter hides the triangles whose mask
  /// (the scene's triangle_masks) shares no bit with `ray_mask`. Only on a
  /// reference built with `exclusion` (std::logic_error otherwise).
  bool intersect_excluding(Vec3f o, Vec3f d, float tnear, float tfar, int32_t exclude, int32_t& prim, float& t,
                           float& u, float& v, uint32_t ray_mask = 0xffffffffu) const;

 private:
  /// rtcIntersect1 of o + t d, t in [tnear, tfar], in `context`: the closest-hit queries' one body.
  bool intersect_in(RTCIntersectContext& context, Vec3f o, Vec3f d, float tnear, float tfar, int32_t& prim,
                    float& t, float& u, float& v) const;

  std::unique_ptr<EmbreeDevice> device_;  // outlives scene_ (released after it)
  RTCScene scene_ = nullptr;
  bool exclusion_ = false;
  std::vector<uint32_t> masks_;  ///< the scene's triangle_masks (empty: all bits)
};

}  // namespace vbsim
