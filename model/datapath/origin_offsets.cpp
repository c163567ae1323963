#include "datapath/origin_offsets.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "datapath/dvec3.h"
#include "datapath/float_bits.h"
#include "datapath/pbrt_interaction.h"

namespace vbsim {

namespace {

bool finite_nonzero(Vec3f n) { return is_finite(n) && (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f); }

Vec3f flip_onto_side(Vec3f u, Vec3f d) { return dot(d, u) < 0.0f ? -u : u; }

/// unit(n) when that is finite, else tri's double-precision normal; false when neither exists.
bool unit_or_double(Vec3f n, const Triangle& tri, Vec3f& unit, OffsetOutcome& outcome) {
  unit = normalize(n);
  if (finite_nonzero(unit)) return true;
  if (unit_normal_in_double(tri, unit)) {
    outcome = OffsetOutcome::NormalInDouble;
    return true;
  }
  outcome = OffsetOutcome::NotOffset;
  return false;
}

/// `moved`, or `p` (counted as NotOffset) when `moved` is not finite.
Vec3f keep_finite(Vec3f p, Vec3f moved, OffsetOutcome& outcome) {
  if (is_finite(moved)) return moved;
  outcome = OffsetOutcome::NotOffset;
  return p;
}

/// The chapter's int(int_scale * n): truncation toward zero, saturated to the
/// int range (the conversion of an out-of-range float is undefined in C++).
int32_t ulps_of(float scaled) {
  if (!(scaled > -2147483648.0f)) return scaled != scaled ? 0 : std::numeric_limits<int32_t>::min();
  if (!(scaled < 2147483648.0f)) return std::numeric_limits<int32_t>::max();
  return static_cast<int32_t>(scaled);
}

}  // namespace

bool unit_normal_in_double(const Triangle& tri, Vec3f& out) {
  const DVec3 n = dcross(to_dvec(tri.v1) - to_dvec(tri.v0), to_dvec(tri.v2) - to_dvec(tri.v0));
  const double len = std::sqrt(ddot(n, n));
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  out = to_vec3f((1.0 / len) * n);
  return true;
}

Vec3f offset_along_normal(Vec3f p, Vec3f n, const Triangle& tri, Vec3f d, float eps, OffsetOutcome& outcome) {
  Vec3f u;
  if (!unit_or_double(n, tri, u, outcome)) return p;
  return keep_finite(p, p + eps * flip_onto_side(u, d), outcome);
}

Vec3f offset_along_direction(Vec3f p, Vec3f d, float eps) { return p + eps * normalize(d); }

Vec3f offset_ray_listing_6_1(Vec3f p, Vec3f n, const AdaptiveOffsetParams& params) {
  Vec3f out;
  for (int i = 0; i < 3; ++i) {
    const uint32_t of = static_cast<uint32_t>(ulps_of(params.int_scale * n[i]));
    // Two's-complement steps on the bit pattern, wrapping as a GPU's 32-bit int does.
    const float p_i = bits_float(float_bits(p[i]) + (p[i] < 0 ? 0u - of : of));
    out[i] = std::fabs(p[i]) < params.origin ? p[i] + params.float_scale * n[i] : p_i;
  }
  return out;
}

Vec3f offset_adaptive(Vec3f p, const Triangle& tri, Vec3f d, const AdaptiveOffsetParams& params,
                      OffsetOutcome& outcome) {
  Vec3f u;
  if (!unit_or_double(geometric_normal(tri), tri, u, outcome)) return p;
  return keep_finite(p, offset_ray_listing_6_1(p, flip_onto_side(u, d), params), outcome);
}

namespace {

/// OffsetRayOrigin(pi, n, d), with a non-finite n replaced by tri's double
/// normal; `before` when there is no normal or no finite result.
Vec3f pbrt_offset_or_before(Vec3f before, const pbrt::PointInterval& pi, Vec3f n, const Triangle& tri, Vec3f d,
                            OffsetOutcome& outcome) {
  if (!finite_nonzero(n)) {
    if (!unit_normal_in_double(tri, n)) {
      outcome = OffsetOutcome::NotOffset;
      return before;
    }
    outcome = OffsetOutcome::NormalInDouble;
  }
  return keep_finite(before, pbrt::offset_ray_origin(pi, n, d), outcome);
}

}  // namespace

Vec3f offset_error_bound(Vec3f before, const Triangle& tri, float b0, float b1, float b2,
                         const std::array<Vec3f, 3>* normals, Vec3f d, OffsetOutcome& outcome) {
  const pbrt::SurfacePoint sp = pbrt::triangle_interaction(tri, b0, b1, b2, normals);
  return pbrt_offset_or_before(before, sp.pi, sp.n, tri, d, outcome);
}

Vec3f offset_error_bound_at(Vec3f p, const Triangle& tri, Vec3f d, OffsetOutcome& outcome) {
  const pbrt::PointInterval pi = pbrt::PointInterval::from_value_and_error(p, pbrt::gamma(7) * abs(p));
  const Vec3f n = pbrt::pbrt_normalize(pbrt::pbrt_cross(tri.v0 - tri.v2, tri.v1 - tri.v2));
  return pbrt_offset_or_before(p, pi, n, tri, d, outcome);
}

}  // namespace vbsim
