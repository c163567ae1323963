// Origin offsets applied at ray emission: the renderer-side self-intersection
// methods. Each takes the parent hit point p and returns the child's origin.
// Side convention: every offset moves p toward the side of the surface the
// child ray leaves into, i.e. along n when dot(d, n) > 0 and along -n otherwise.
#pragma once
#include "datapath/self_intersection_method.h"
#include "datapath/triangle.h"
#include "datapath/vec3.h"

namespace vbsim {

/// p + eps * unit(n), with n flipped onto the side of d (offset-normal).
Vec3f offset_along_normal(Vec3f p, Vec3f n, Vec3f d, float eps);
/// p + eps * unit(d) (offset-direction).
Vec3f offset_along_direction(Vec3f p, Vec3f d, float eps);
/// Ray Tracing Gems ch. 6, Listing 6-1: an integer-ulp offset of each component
/// along unit(n) (n flipped onto the side of d), a float offset for components
/// nearer to zero than params.origin.
Vec3f offset_adaptive(Vec3f p, Vec3f n, Vec3f d, const AdaptiveOffsetParams& params);

/// A point computed by barycentric interpolation with its conservative
/// per-component absolute error bound (pbrt-v4: gamma(7) * sum |b_i p_i|).
struct BoundedPoint {
  Vec3f p;
  Vec3f error;
};
BoundedPoint barycentric_point_with_error(const Triangle& tri, float u, float v);
/// pbrt-v4's OffsetRayOrigin: offset by dot(|unit Ng|, error) along unit Ng on
/// the side of d, then each offset component rounded one float further outward.
Vec3f offset_error_bound(const BoundedPoint& pt, Vec3f ng, Vec3f d);

}  // namespace vbsim
