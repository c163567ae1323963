#include "datapath/origin_offsets.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace vbsim {

namespace {

Vec3f unit_on_side(Vec3f n, Vec3f d) {
  const Vec3f u = normalize(n);
  return dot(d, u) < 0.0f ? -u : u;
}

int32_t float_as_int(float f) {
  int32_t i;
  std::memcpy(&i, &f, sizeof i);
  return i;
}

float int_as_float(int32_t i) {
  float f;
  std::memcpy(&f, &i, sizeof f);
  return f;
}

/// gamma(n) = n u / (1 - n u), u = 2^-24: the relative error bound of n roundings.
constexpr float gamma(int n) {
  constexpr float u = std::numeric_limits<float>::epsilon() * 0.5f;
  return (n * u) / (1 - n * u);
}

}  // namespace

Vec3f offset_along_normal(Vec3f p, Vec3f n, Vec3f d, float eps) {
  return p + eps * unit_on_side(n, d);
}

Vec3f offset_along_direction(Vec3f p, Vec3f d, float eps) { return p + eps * normalize(d); }

Vec3f offset_adaptive(Vec3f p, Vec3f n, Vec3f d, const AdaptiveOffsetParams& params) {
  const Vec3f nn = unit_on_side(n, d);
  Vec3f out;
  for (int i = 0; i < 3; ++i) {
    const int32_t of = static_cast<int32_t>(params.int_scale * nn[i]);
    const float p_i = int_as_float(float_as_int(p[i]) + (p[i] < 0 ? -of : of));
    out[i] = std::fabs(p[i]) < params.origin ? p[i] + params.float_scale * nn[i] : p_i;
  }
  return out;
}

BoundedPoint barycentric_point_with_error(const Triangle& tri, float u, float v) {
  const float w = 1.0f - u - v;
  BoundedPoint out;
  out.p = w * tri.v0 + u * tri.v1 + v * tri.v2;
  out.error = gamma(7) * (abs(w * tri.v0) + abs(u * tri.v1) + abs(v * tri.v2));
  return out;
}

Vec3f offset_error_bound(const BoundedPoint& pt, Vec3f ng, Vec3f d) {
  const Vec3f n = normalize(ng);
  const float dist = dot(abs(n), pt.error);
  Vec3f offset = dist * n;
  if (dot(d, n) < 0.0f) offset = -offset;
  Vec3f po = pt.p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0.0f) po[i] = std::nextafter(po[i], std::numeric_limits<float>::infinity());
    else if (offset[i] < 0.0f) po[i] = std::nextafter(po[i], -std::numeric_limits<float>::infinity());
  }
  return po;
}

}  // namespace vbsim
