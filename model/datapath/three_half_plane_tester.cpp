// The patent's three-half-plane ray/triangle test (US 8,441,482: "the three half
// plane ray/triangle intersection test produces a bit ... whether the ray hit a
// front side or a back side"), evaluated watertight as in Woop, Benthin and Wald,
// "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013.
//
// The three half-planes: for each edge, the plane through the ray origin and that
// edge. The ray direction is on the same side of all three planes exactly when the
// ray passes through the triangle, and which side that is tells front from back.
// In the sheared ray space below the direction becomes +z, so the side of d
// against the plane through o and edge (P, Q) is the sign of the 2-D edge function
// Qx*Py - Qy*Px of the sheared, translated vertices.
//
// Front bit. With Ng = (v1-v0) x (v2-v0) and M the (permute, shear) map of the
// set-up, M d = (0, 0, d[kz]) and det(M) = det(permutation). For any a, b the
// 2-D cross product of their images is
//   [(M a) x (M b)]_z = det(M) (a x b) . (M^-1 e_z) = det(perm) (a x b) . d / d[kz].
// The edge functions are U + V + W = -[(B-A) x (C-A)]_z in sheared space, so
//   det = -det(perm) dot(d, Ng) / d[kz] = -dot(d, Ng) / |d[kz]|,
// because (kx, ky, kz) is a cyclic (det +1) order unless d[kz] < 0, where the swap
// makes det(perm) = -1. Hence det > 0  <=>  dot(d, Ng) < 0  <=>  front = 1.
// (Checked against an independent dot(d, Ng) in three_half_plane_tester_test.cpp.)
#include <cmath>

#include "datapath/testers.h"

namespace vbsim {

bool ThreeHalfPlaneTester::intersect(const Triangle& tri, float tmax, Hit& hit) const {
  // Vertices relative to the ray origin, then sheared so that d becomes +z.
  // (Plain arrays: indexing them by kx/ky/kz is a load, not a chain of selects.)
  const float a[3] = {tri.v0.x - o_.x, tri.v0.y - o_.y, tri.v0.z - o_.z};
  const float b[3] = {tri.v1.x - o_.x, tri.v1.y - o_.y, tri.v1.z - o_.z};
  const float c[3] = {tri.v2.x - o_.x, tri.v2.y - o_.y, tri.v2.z - o_.z};
  const float ax = a[kx_] - sx_ * a[kz_];
  const float ay = a[ky_] - sy_ * a[kz_];
  const float bx = b[kx_] - sx_ * b[kz_];
  const float by = b[ky_] - sy_ * b[kz_];
  const float cx = c[kx_] - sx_ * c[kz_];
  const float cy = c[ky_] - sy_ * c[kz_];

  // Edge functions (the three half-plane sides). U: edge v1->v2 (weight of v0),
  // V: edge v2->v0 (weight of v1), W: edge v0->v1 (weight of v2). A shared edge
  // gives bit-identical values of opposite sign in its two triangles.
  float e_u = cx * by - cy * bx;
  float e_v = ax * cy - ay * cx;
  float e_w = bx * ay - by * ax;

  // An exactly-zero edge function may be a rounding artefact: redo all three
  // with exact products (24x24-bit products are exact in double).
  if (e_u == 0.0f || e_v == 0.0f || e_w == 0.0f) {
    e_u = static_cast<float>(double(cx) * double(by) - double(cy) * double(bx));
    e_v = static_cast<float>(double(ax) * double(cy) - double(ay) * double(cx));
    e_w = static_cast<float>(double(bx) * double(ay) - double(by) * double(ax));
  }

  // Mixed signs: d is on different sides of two of the planes, a miss.
  if ((e_u < 0.0f || e_v < 0.0f || e_w < 0.0f) && (e_u > 0.0f || e_v > 0.0f || e_w > 0.0f))
    return false;
  const float det = e_u + e_v + e_w;
  if (det == 0.0f) return false;  // the ray lies in the triangle's plane (or degenerate)

  // Scaled distance: t = T / det.
  const float az = sz_ * a[kz_];
  const float bz = sz_ * b[kz_];
  const float cz = sz_ * c[kz_];
  const float t_scaled = e_u * az + e_v * bz + e_w * cz;

  // tmin < T/det < tmax tested without division: multiply through by |det|.
  const float abs_det = std::fabs(det);
  const float t_signed = det < 0.0f ? -t_scaled : t_scaled;
  if (!(t_signed > tmin_ * abs_det) || !(t_signed < tmax * abs_det)) return false;

  const float t = t_scaled / det;
  // The scaled test is the early out; the t reported must itself obey the open
  // interval, so a closest-hit search never takes a hit at its current tmax.
  if (!(t > tmin_ && t < tmax)) return false;

  hit.t = t;
  hit.u = e_v / det;
  hit.v = e_w / det;
  hit.front = det > 0.0f ? 1 : 0;
  return true;
}

}  // namespace vbsim
