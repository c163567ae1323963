// Which rays of a capture the trace cannot reproduce, and why (the trace's
// `incomplete` field, trace/incomplete_reasons.h):
//   - an intersect query whose Embree hit lies on geometry the trace's scene
//     does not hold (inside an instance, a quad, curve, user, grid, point or
//     subdivision geometry, a motion-blurred or otherwise uncaptured mesh);
//   - an occlusion query Embree found occluded, in a scene holding such
//     geometry, that the captured triangles alone do not occlude (Embree's
//     own test on them): it is marked with every kind the scene holds outside
//     the trace, since Embree does not say what occluded it;
//   - any query during which one of the application's geometry filter
//     functions rejected or changed a candidate hit, or whose intersect
//     context carried a filter function (the shim does not see what those
//     decided), or every query when the shim could not watch all filter
//     functions.
//   - in a scene with instances (flattened into world-space triangles), any
//     query whose answer on the flattened triangles (Embree's robust test on
//     them) is not the application's: the flattened float arithmetic is not
//     Embree's instance-space test.
// Otherwise a miss, a hit on a captured triangle (Embree reports the closest
// hit) and an unoccluded shadow ray are what the captured scene gives.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "capture/captured_scene.h"
#include "capture/raw_capture_format.h"
#include "scene/embree_reference.h"

namespace vbsim::capture {

/// The IncompleteReason bit of a geometry the trace does not hold (0 for a
/// captured or a disabled one, which Embree does not trace).
uint32_t incomplete_reason_of(const CapturedGeometry& g);

class IncompleteRayJudge {
 public:
  /// `unwatched_filters`: the process set filter functions the shim could not wrap.
  /// `ray_masks`: the application's Embree honours ray masks (a build option,
  /// RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED); without them it tests every
  /// geometry whatever the masks, so no ray is marked `mask`.
  IncompleteRayJudge(const CapturedScene& scene, bool unwatched_filters, bool ray_masks = true);
  ~IncompleteRayJudge();

  /// IncompleteReason bits of `r`, a ray traced against `scene` (0: the trace reproduces its answer).
  uint32_t reasons(const RawRay& r) const;

  /// Reasons of every geometry of the scene outside the trace.
  uint32_t uncaptured_kinds() const { return uncaptured_kinds_; }
  /// In a scene with flattened instances: the rays checked against Embree's
  /// answer on the flattened triangles, and those whose answer differed
  /// (marked `instance`).
  int64_t flattened_checked() const { return flattened_checked_; }
  int64_t flattened_differs() const { return flattened_differs_; }

 private:
  const CapturedScene& scene_;
  bool unwatched_filters_;
  uint32_t uncaptured_kinds_ = 0;
  std::vector<uint32_t> reason_by_geom_;           ///< geomID -> reason bit
  std::vector<uint32_t> masks_;                    ///< the distinct masks of the captured geometries
  std::unique_ptr<EmbreeReference> captured_only_;  ///< the captured triangles, when anything is outside
  mutable int64_t flattened_checked_ = 0, flattened_differs_ = 0;
};

}  // namespace vbsim::capture
