// Möller–Trumbore (1997) ray/triangle test in float32, in the form the renderer
// blog (source document 004) writes it: Cramer's rule on
//   o + t d = (1-u-v) v0 + u v1 + v v2,
// with e1 = v1-v0, e2 = v2-v0, s = o-v0, p = d x e2, q = s x e1:
//   det = e1.p,  u = s.p / det,  v = d.q / det,  t = e2.q / det.
// No culling: only det == 0 exactly is rejected (the blog's test). Bounds:
// 0 <= u <= 1, v >= 0, u+v <= 1, and the contract's open interval tmin < t < tmax
// (the blog closes it). Comparisons are written so that a NaN rejects.
//
// Front bit: det = e1 . (d x e2) = d . (e2 x e1) = -d . (e1 x e2) = -dot(d, Ng),
// so det > 0 <=> dot(d, Ng) < 0 <=> front = 1 (checked against an independent
// dot(d, Ng) in moller_trumbore_tester_test.cpp).
//
// Not watertight: the two triangles of a shared edge compute u, v from different
// vertices and products, so a ray through the edge can fail both bound tests.
#include "datapath/testers.h"

namespace vbsim {

MollerTrumboreTester::MollerTrumboreTester(const Ray& ray)
    : o_(ray.o), d_(ray.d), tmin_(ray.tmin) {}

bool MollerTrumboreTester::intersect(const Triangle& tri, float tmax, Hit& hit) const {
  const Vec3f e1 = tri.v1 - tri.v0;
  const Vec3f e2 = tri.v2 - tri.v0;
  const Vec3f p = cross(d_, e2);
  const float det = dot(e1, p);
  if (det == 0.0f) return false;
  const float inv_det = 1.0f / det;

  const Vec3f s = o_ - tri.v0;
  const float u = dot(s, p) * inv_det;
  if (!(u >= 0.0f && u <= 1.0f)) return false;

  const Vec3f q = cross(s, e1);
  const float v = dot(d_, q) * inv_det;
  if (!(v >= 0.0f && u + v <= 1.0f)) return false;

  const float t = dot(e2, q) * inv_det;
  if (!(t > tmin_ && t < tmax)) return false;

  hit.t = t;
  hit.u = u;
  hit.v = v;
  hit.front = det > 0.0f ? 1 : 0;
  return true;
}

}  // namespace vbsim
