#include "capture/incomplete_rays.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "trace/incomplete_reasons.h"

namespace vbsim::capture {

uint32_t incomplete_reason_of(const CapturedGeometry& g) {
  switch (g.status) {
    case RawGeometryStatus::Captured:
    case RawGeometryStatus::Disabled:
      return 0;
    case RawGeometryStatus::MotionBlur:
      return kIncompleteMotionBlur;
    case RawGeometryStatus::NestedInstance:
      return kIncompleteInstance;
    case RawGeometryStatus::MissingBuffer:
    case RawGeometryStatus::BadFormat:
      return g.type == RTC_GEOMETRY_TYPE_INSTANCE ? kIncompleteInstance : kIncompleteOtherGeometry;
    case RawGeometryStatus::NotTriangles:
      break;
  }
  switch (g.type) {  // RTCGeometryType
    case RTC_GEOMETRY_TYPE_QUAD: return kIncompleteQuad;
    case RTC_GEOMETRY_TYPE_GRID: return kIncompleteGrid;
    case RTC_GEOMETRY_TYPE_SUBDIVISION: return kIncompleteSubdivision;
    case RTC_GEOMETRY_TYPE_SPHERE_POINT:
    case RTC_GEOMETRY_TYPE_DISC_POINT:
    case RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT: return kIncompletePoint;
    case RTC_GEOMETRY_TYPE_USER: return kIncompleteUser;
    case RTC_GEOMETRY_TYPE_INSTANCE: return kIncompleteInstance;
    default: return std::string(embree_geometry_type_name(g.type)) == "curve" ? kIncompleteCurve : kIncompleteOtherGeometry;
  }
}

IncompleteRayJudge::IncompleteRayJudge(const CapturedScene& scene, bool unwatched_filters, int on_surface_ulps,
                                       bool ray_masks)
    : scene_(scene), unwatched_filters_(unwatched_filters), ray_masks_(ray_masks) {
  float extent = 0.0f;
  for (const Triangle& t : scene.triangles())
    for (const Vec3f& v : {t.v0, t.v1, t.v2})
      for (int a = 0; a < 3; ++a)
        if (std::isfinite(v[a])) extent = std::max(extent, std::fabs(v[a]));
  on_surface_radius_ = on_surface_ulps * (std::nextafter(extent, INFINITY) - extent);
  if (!scene.triangles().empty()) surfaces_ = std::make_unique<SurfaceProximity>(scene.triangles());
  for (const CapturedGeometry& g : scene.geometries()) {
    const uint32_t r = incomplete_reason_of(g);
    uncaptured_kinds_ |= r;
    if (reason_by_geom_.size() <= g.geom_id) reason_by_geom_.resize(g.geom_id + 1, 0);
    reason_by_geom_[g.geom_id] = r;
  }
  if (ray_masks) {
    unheld_masks_ = scene.unheld_masks();
    triangle_masks_used_ = std::any_of(scene.triangle_masks().begin(), scene.triangle_masks().end(),
                                       [](uint32_t m) { return m != kAllMaskBits; });
  }
  if ((uncaptured_kinds_ != 0 || scene.has_instances()) && !scene.triangles().empty()) {
    Scene flattened = make_scene(scene.triangles());
    flattened.triangle_masks = triangle_masks();
    captured_only_ = std::make_unique<EmbreeReference>(flattened, "", true);
  }
}

IncompleteRayJudge::~IncompleteRayJudge() = default;

bool IncompleteRayJudge::self_excluded(const RawRay& r, const RawRay* parent) {
  return parent && filters_rejected_hit(r, *parent);
}

uint32_t IncompleteRayJudge::reasons(const RawRay& r, const RawRay* parent) const {
  uint32_t bits = 0;
  const bool excluded = self_excluded(r, parent);
  self_excluded_rays_ += excluded;
  if (unwatched_filters_ || (r.flags & (kRawFilterChanged | kRawContextFilter)) ||
      ((r.flags & kRawFilterRejected) && !excluded))
    bits |= kIncompleteFilter;
  // The triangle the renderer's filter kept this ray from hitting: a replay
  // with the same exclusion (primid) gives the application's answer.
  const int32_t exclude = excluded || (renderer_excludes_parents_ && parent)
                              ? static_cast<int32_t>(scene_.triangle_hit(*parent).triangle)
                              : -1;
  if (!parent && surfaces_ && surfaces_->within({r.org[0], r.org[1], r.org[2]}, on_surface_radius_))
    bits |= kIncompleteUnlinked;
  // An instanced geometry whose instance and geometry masks the trace cannot
  // both hold (it holds the geometry's): a ray that shares a bit with the
  // geometry's but none with the instance's would see in a replay what Embree
  // did not test.
  for (const auto& [instance, geometry] : unheld_masks_)
    if ((r.mask & geometry) != 0 && (r.mask & instance) == 0) bits |= kIncompleteMask;
  int32_t prim = -1;
  float t = 0.0f, u, v;
  auto captured_answer = [&] {  // Embree's closest hit on the trace's triangles
    return captured_only_ && captured_only_->intersect_excluding({r.org[0], r.org[1], r.org[2]},
                                                                 {r.dir[0], r.dir[1], r.dir[2]}, r.tnear, r.tfar,
                                                                 exclude, prim, t, u, v, ray_mask(r));
  };
  if (r.op == static_cast<uint16_t>(RawOp::Intersect)) {
    const TriangleHit h = scene_.triangle_hit(r);
    if (r.geom != kInvalidId && h.triangle < 0) {  // geometry the trace does not hold
      if (r.inst != kInvalidId) return bits | kIncompleteInstance;
      const uint32_t g = r.geom < reason_by_geom_.size() ? reason_by_geom_[r.geom] : 0;
      return bits | (g != 0 ? g : kIncompleteOtherGeometry);
    }
    if (!scene_.has_instances()) return bits;  // a miss, or the closest hit on a triangle the trace holds
    // Marked for masks the trace cannot hold: the flattened answer, with the
    // geometry's mask alone, differs for that reason, not for the instance.
    if (bits & kIncompleteMask) return bits;
    // With flattened instances the trace's triangles are not the ones Embree
    // tested (it transformed the ray instead): the flattened answer must agree.
    ++flattened_checked_;
    const bool hit = captured_answer();
    const bool same = r.geom == kInvalidId ? !hit
                                            : hit && (prim == h.triangle || std::fabs(t - r.hit_t) <= 1e-6f * r.hit_t);
    if (!same) ++flattened_differs_;
    return same ? bits : bits | kIncompleteInstance;
  }
  const bool occluded = std::isinf(r.hit_t) && r.hit_t < 0;
  if (!scene_.has_instances() && (!occluded || uncaptured_kinds_ == 0)) return bits;
  if (bits & kIncompleteMask) return bits;  // as above
  if (scene_.has_instances()) ++flattened_checked_;
  const bool by_captured = captured_answer();
  if (by_captured == occluded) return bits;
  if (scene_.has_instances()) ++flattened_differs_;
  return bits | uncaptured_kinds_ | (scene_.has_instances() ? kIncompleteInstance : 0u);
}

}  // namespace vbsim::capture
