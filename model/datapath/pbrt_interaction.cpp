#include "datapath/pbrt_interaction.h"

#include <cmath>

namespace vbsim::pbrt {

namespace {

Vec3f abs3(Vec3f a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }

}  // namespace

SurfacePoint triangle_interaction(const Triangle& tri, float b0, float b1, float b2,
                                  const std::array<Vec3f, 3>* normals) {
  const Vec3f& p0 = tri.v0;
  const Vec3f& p1 = tri.v1;
  const Vec3f& p2 = tri.v2;
  const Vec3f p_hit = b0 * p0 + b1 * p1 + b2 * p2;
  const Vec3f abs_sum = abs3(b0 * p0) + abs3(b1 * p1) + abs3(b2 * p2);
  SurfacePoint sp;
  sp.pi = PointInterval::from_value_and_error(p_hit, gamma(7) * abs_sum);
  sp.n = pbrt_normalize(pbrt_cross(p0 - p2, p1 - p2));
  if (normals) {
    Vec3f ns = b0 * (*normals)[0] + b1 * (*normals)[1] + b2 * (*normals)[2];
    ns = pbrt_length_squared(ns) > 0 ? pbrt_normalize(ns) : sp.n;
    sp.n = face_forward(sp.n, ns);
  }
  return sp;
}

Vec3f offset_ray_origin(const PointInterval& pi, Vec3f n, Vec3f w) {
  const float d = pbrt_dot(abs3(n), pi.error());
  Vec3f offset = d * n;
  if (pbrt_dot(w, n) < 0) offset = -offset;
  Vec3f po = pi.point() + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0) po[i] = next_float_up(po[i]);
    else if (offset[i] < 0) po[i] = next_float_down(po[i]);
  }
  return po;
}

}  // namespace vbsim::pbrt
