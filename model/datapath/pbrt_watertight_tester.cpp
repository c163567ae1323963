// pbrt-v4's ray/triangle test (src/pbrt/shapes.cpp, IntersectTriangle), in the
// float32 operations and order pbrt-v4 uses (datapath/pbrt_float.h):
//   - a triangle whose pbrt_cross(v2 - v0, v1 - v0) has zero squared length is no hit;
//   - vertices minus the origin, permuted by kz = the largest |d| component,
//     kx = kz + 1, ky = kx + 1 (mod 3), with no swap when d[kz] < 0, sheared by
//     Sx = -d[kx] / d[kz], Sy = -d[ky] / d[kz] (x += Sx z, y += Sy z);
//   - edge functions e0 = DoP(p1.x, p2.y, p1.y, p2.x), e1 = DoP(p2.x, p0.y, p2.y, p0.x),
//     e2 = DoP(p0.x, p1.y, p0.y, p1.x), redone in double when one is exactly 0;
//   - mixed signs or det = e0 + e1 + e2 = 0: no hit; z scaled by Sz = 1 / d[kz];
//     tScaled = e0 z0 + e1 z1 + e2 z2 must have det's sign and |tScaled| <= tMax |det|;
//   - invDet = 1 / det, b_i = e_i invDet, t = tScaled invDet;
//   - the bound deltaT of t's own rounding error (gamma(3) / gamma(5) terms) and
//     t <= deltaT: no hit.
//
// Front bit. With M the (permute, shear) map of the set-up (det(M) = +1: the
// permutation is cyclic and never swapped), [(M a) x (M b)]_z = (a x b) . d / d[kz]
// (M^-1 e_z = d / d[kz]), and e0 + e1 + e2 is that 2-D cross product of the
// edges v1 - v0, v2 - v0: det = dot(d, Ng) / d[kz]. So front (dot(d, Ng) < 0)
// is det > 0 exactly when d[kz] < 0 (checked against an independent dot(d, Ng)
// in pbrt_watertight_tester_test.cpp).
#include <cmath>

#include "datapath/pbrt_float.h"
#include "datapath/testers.h"

namespace vbsim {

namespace {

float max_abs3(float a, float b, float c) {
  const float x = std::fabs(a), y = std::fabs(b), z = std::fabs(c);
  return x > y ? (x > z ? x : z) : (y > z ? y : z);
}

}  // namespace

PbrtWatertightTester::PbrtWatertightTester(const Ray& ray) : o_(ray.o), tmin_(ray.tmin) {
  kz_ = max_dimension(ray.d);
  kx_ = kz_ + 1 == 3 ? 0 : kz_ + 1;
  ky_ = kx_ + 1 == 3 ? 0 : kx_ + 1;
  sx_ = -ray.d[kx_] / ray.d[kz_];
  sy_ = -ray.d[ky_] / ray.d[kz_];
  sz_ = 1.0f / ray.d[kz_];
  dz_negative_ = ray.d[kz_] < 0.0f;
}

bool PbrtWatertightTester::intersect_triangle(const Triangle& tri, float tmax, PbrtTriangleHit& out) const {
  using namespace pbrt;
  if (pbrt_length_squared(pbrt_cross(tri.v2 - tri.v0, tri.v1 - tri.v0)) == 0.0f) return false;

  const Vec3f q0 = tri.v0 - o_, q1 = tri.v1 - o_, q2 = tri.v2 - o_;
  float p0x = q0[kx_], p0y = q0[ky_], p0z = q0[kz_];
  float p1x = q1[kx_], p1y = q1[ky_], p1z = q1[kz_];
  float p2x = q2[kx_], p2y = q2[ky_], p2z = q2[kz_];
  p0x += sx_ * p0z;
  p0y += sy_ * p0z;
  p1x += sx_ * p1z;
  p1y += sy_ * p1z;
  p2x += sx_ * p2z;
  p2y += sy_ * p2z;

  float e0 = difference_of_products(p1x, p2y, p1y, p2x);
  float e1 = difference_of_products(p2x, p0y, p2y, p0x);
  float e2 = difference_of_products(p0x, p1y, p0y, p1x);
  if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
    e0 = static_cast<float>(double(p2y) * double(p1x) - double(p2x) * double(p1y));
    e1 = static_cast<float>(double(p0y) * double(p2x) - double(p0x) * double(p2y));
    e2 = static_cast<float>(double(p1y) * double(p0x) - double(p1x) * double(p0y));
  }
  if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return false;
  const float det = e0 + e1 + e2;
  if (det == 0) return false;

  p0z *= sz_;
  p1z *= sz_;
  p2z *= sz_;
  const float t_scaled = e0 * p0z + e1 * p1z + e2 * p2z;
  if (det < 0 && (t_scaled >= 0 || t_scaled < tmax * det)) return false;
  if (det > 0 && (t_scaled <= 0 || t_scaled > tmax * det)) return false;

  const float inv_det = 1 / det;
  const float t = t_scaled * inv_det;

  // pbrt's bound of t's rounding error.
  const float max_zt = max_abs3(p0z, p1z, p2z);
  const float delta_z = gamma(3) * max_zt;
  const float max_xt = max_abs3(p0x, p1x, p2x);
  const float max_yt = max_abs3(p0y, p1y, p2y);
  const float delta_x = gamma(5) * (max_xt + max_zt);
  const float delta_y = gamma(5) * (max_yt + max_zt);
  const float delta_e = 2 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  const float max_e = max_abs3(e0, e1, e2);
  const float delta_t = 3 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * std::fabs(inv_det);
  if (!(t > delta_t)) return false;  // pbrt: t <= deltaT; written so that a NaN t is no hit either

  out.b0 = e0 * inv_det;
  out.b1 = e1 * inv_det;
  out.b2 = e2 * inv_det;
  out.t = t;
  out.front = (det > 0) == dz_negative_;
  return true;
}

bool PbrtWatertightTester::intersect(const Triangle& tri, float tmax, Hit& hit) const {
  PbrtTriangleHit h;
  if (!intersect_triangle(tri, tmax, h)) return false;
  if (!(h.t > tmin_ && h.t < tmax)) return false;  // the contract's open interval
  hit.t = h.t;
  hit.u = h.b1;
  hit.v = h.b2;
  hit.front = h.front ? 1 : 0;
  return true;
}

}  // namespace vbsim
