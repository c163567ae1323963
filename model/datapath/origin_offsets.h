// Origin offsets applied at ray emission: the renderer-side self-intersection
// methods. Each takes the parent hit point p and returns the child's origin.
// Side convention: every offset moves p toward the side of the surface the
// child ray leaves into, i.e. along n when dot(d, n) > 0 and along -n otherwise.
//
// Degenerate normals (docs/methods.md): a method's float32 unit normal is not
// finite when the cross product is 0 (a zero-area triangle, or one so small
// that it underflows: 1e-30 and denormal coordinates) or overflows (3e38
// coordinates), since normalising then divides 0 by 0 or inf by inf. Such a ray
// gets a defined outcome, reported as an OffsetOutcome: the unit normal is
// recomputed from the same float vertices in double precision (finite for any
// triangle with non-collinear vertices); when even that has no direction, or
// when the offset origin is not finite (a 3e38 triangle's error bound
// overflows), the origin is the point the method was given.
#pragma once
#include <array>
#include <cstdint>

#include "datapath/self_intersection_method.h"
#include "datapath/testers.h"
#include "datapath/triangle.h"
#include "datapath/vec3.h"

namespace vbsim {

/// How an offset method placed a ray's origin.
enum class OffsetOutcome : uint8_t {
  Reference,       ///< the reference's own arithmetic
  NormalInDouble,  ///< its float normal was not finite: the double-precision unit normal was used
  NotOffset,       ///< no direction to offset along, or a non-finite result: origin unchanged
};

/// Unit geometric normal of `tri` from its float vertices in double precision,
/// rounded to float; false when the cross product is 0 (collinear vertices).
bool unit_normal_in_double(const Triangle& tri, Vec3f& out);

/// p + eps * unit(n), with n flipped onto the side of d (offset-normal). A
/// non-finite unit(n) takes `tri`'s double-precision normal instead.
Vec3f offset_along_normal(Vec3f p, Vec3f n, const Triangle& tri, Vec3f d, float eps, OffsetOutcome& outcome);
/// p + eps * unit(d) (offset-direction).
Vec3f offset_along_direction(Vec3f p, Vec3f d, float eps);
/// Ray Tracing Gems ch. 6, Listing 6-1, along the unit geometric normal of
/// `tri` (float cross (v1 - v0) x (v2 - v0) times 1 / length, flipped onto the
/// side of d): each component moves int_scale * n ulps away from the integer
/// representation's zero, or float_scale * n where |p| < origin.
Vec3f offset_adaptive(Vec3f p, const Triangle& tri, Vec3f d, const AdaptiveOffsetParams& params,
                      OffsetOutcome& outcome);
/// Listing 6-1 itself on a unit normal `n` already on the side of the ray
/// (integer steps wrap as the chapter's GPU integers do; a scale beyond the
/// int range saturates).
Vec3f offset_ray_listing_6_1(Vec3f p, Vec3f n, const AdaptiveOffsetParams& params);

/// pbrt-v4's spawn origin (offset-errbound) for a hit at barycentrics (b0, b1,
/// b2) of `tri` (pbrt_interaction.h): the interval point, OffsetRayOrigin along
/// the unit normal face-forwarded to `normals` when given, on the side of d.
/// `before` is the origin kept when the outcome is NotOffset.
Vec3f offset_error_bound(Vec3f before, const Triangle& tri, float b0, float b1, float b2,
                         const std::array<Vec3f, 3>* normals, Vec3f d, OffsetOutcome& outcome);
/// offset-errbound without barycentrics: `p` with pbrt's bound gamma(7) |p|
/// per component, along `tri`'s pbrt normal.
Vec3f offset_error_bound_at(Vec3f p, const Triangle& tri, Vec3f d, OffsetOutcome& outcome);

}  // namespace vbsim
