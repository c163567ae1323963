// Which rays of a capture the trace cannot reproduce, and why (the trace's
// `incomplete` field, trace/incomplete_reasons.h):
//   - an intersect query whose Embree hit lies on geometry the trace's scene
//     does not hold (inside an instance, a quad, curve, user, grid, point or
//     subdivision geometry, a motion-blurred or otherwise uncaptured mesh);
//   - an occlusion query Embree found occluded, in a scene holding such
//     geometry, that the captured triangles alone do not occlude (Embree's
//     own test on them): it is marked with every kind the scene holds outside
//     the trace, since Embree does not say what occluded it;
//   - any query during which the application's filter functions (on a
//     geometry or in the intersect context) changed the answer other than by
//     rejecting the ray's own parent primitive (the renderer's self-exclusion,
//     which `primid` reproduces: such a ray is scoreable and counted as
//     self-excluded), or every query when the shim could not watch all filter
//     functions;
//   - a ray with no parent whose origin lies on a surface of the scene
//     (within `on_surface_ulps` ulps of the scene's largest coordinate): a
//     secondary ray the capture could not link, which scored as a camera ray
//     would expect the surface it leaves as its answer (`unlinked`);
//   - in a scene with instances (flattened into world-space triangles), any
//     query whose answer on the flattened triangles (Embree's robust test on
//     them, with the parent's triangle excluded when the renderer excluded
//     it) is not the application's: the flattened float arithmetic is not
//     Embree's instance-space test.
// Otherwise a miss, a hit on a captured triangle (Embree reports the closest
// hit) and an unoccluded shadow ray are what the captured scene gives.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "capture/captured_scene.h"
#include "trace/trace_record.h"
#include "capture/raw_capture_format.h"
#include "scene/embree_reference.h"
#include "scene/surface_proximity.h"

namespace vbsim::capture {

/// The IncompleteReason bit of a geometry the trace does not hold (0 for a
/// captured or a disabled one, which Embree does not trace).
uint32_t incomplete_reason_of(const CapturedGeometry& g);

class IncompleteRayJudge {
 public:
  /// `unwatched_filters`: the process set filter functions the shim could not wrap.
  /// `on_surface_ulps`: a parentless ray within this many ulps of the scene's
  /// largest coordinate from a triangle starts on a surface (marked `unlinked`).
  /// `ray_masks`: the application's Embree honours ray masks (a build option,
  /// RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED): the trace then carries the
  /// triangles' and rays' masks (ray_mask(), triangle_masks()), and only a ray
  /// whose instance's mask the trace cannot hold is marked `mask`; without
  /// them Embree tests every geometry whatever the masks, and so does the trace.
  IncompleteRayJudge(const CapturedScene& scene, bool unwatched_filters, int on_surface_ulps, bool ray_masks = true);
  ~IncompleteRayJudge();

  /// IncompleteReason bits of `r`, a ray traced against `scene` (0: the trace
  /// reproduces its answer); `parent`: the hit `r` is linked to, or null.
  uint32_t reasons(const RawRay& r, const RawRay* parent) const;

  /// Whether the application's filters rejected candidates of `r` on its
  /// parent's primitive only (primitive-ID exclusion, as Cycles does).
  static bool self_excluded(const RawRay& r, const RawRay* parent);
  /// The application excludes a ray's parent primitive (its filters were
  /// seen doing so): the flattened re-check of every linked ray excludes the
  /// parent's triangle, whether or not Embree offered it to the filter.
  void set_renderer_excludes_parents(bool on) { renderer_excludes_parents_ = on; }
  /// Distance within which a parentless ray's origin is on a surface.
  float on_surface_radius() const { return on_surface_radius_; }
  /// Rays judged so far whose filters rejected their parent's primitive only.
  int64_t self_excluded_rays() const { return self_excluded_rays_; }

  /// The mask `r` carries in the trace: its own when Embree honours masks, else all bits.
  uint32_t ray_mask(const RawRay& r) const { return ray_masks_ ? r.mask : kAllMaskBits; }
  /// The triangles' masks the trace declares (empty: all bits, or masks not honoured).
  const std::vector<uint32_t>& triangle_masks() const {
    static const std::vector<uint32_t> all_bits;
    return triangle_masks_used_ ? scene_.triangle_masks() : all_bits;
  }

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
  bool ray_masks_;                                  ///< Embree honours ray masks
  bool triangle_masks_used_ = false;                ///< masks honoured and some triangle's not all bits
  std::vector<std::pair<uint32_t, uint32_t>> unheld_masks_;  ///< CapturedScene::unheld_masks()
  std::unique_ptr<EmbreeReference> captured_only_;  ///< the captured triangles, when anything is outside
  std::unique_ptr<SurfaceProximity> surfaces_;      ///< the captured triangles, for parentless origins
  float on_surface_radius_ = 0.0f;
  bool renderer_excludes_parents_ = false;
  mutable int64_t flattened_checked_ = 0, flattened_differs_ = 0, self_excluded_rays_ = 0;
};

}  // namespace vbsim::capture
