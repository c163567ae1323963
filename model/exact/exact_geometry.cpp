#include "exact/exact_geometry.h"

#include "exact/exact_plane.h"

#include <cmath>
#include <stdexcept>

namespace vbsim {

namespace {

// Rationals reused across calls (one set per thread) so that the exact test
// does not reallocate limbs on every call; results are copied out.
struct ExactScratch {
  mpq_class m[3];    // o x d
  mpq_class mv[3];   // m . v_k
  mpq_class vc[3];   // v_k x v_{k+1} (one component at a time)
  mpq_class ng[3];   // Ng = sum of the three v_k x v_{k+1}
  mpq_class e[3];    // edge functions
  mpq_class p, q, den, num;
};
thread_local ExactScratch scratch;

double component(const Triangle& tri, int k, int axis) {
  const Vec3f& v = k == 0 ? tri.v0 : (k == 1 ? tri.v1 : tri.v2);
  return static_cast<double>(v[axis]);
}

const mpq_class& component(const ExactVec3& v, int axis) {
  return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

void require_finite(Vec3f v, const char* what) {
  if (!is_finite(v)) throw std::invalid_argument(std::string("exact geometry: non-finite ") + what);
}

// out = a . b for rationals, using `tmp` as the only temporary.
void dot_into(mpq_class& out, const mpq_class* a, const ExactVec3& b, mpq_class& tmp) {
  mpq_mul(out.get_mpq_t(), a[0].get_mpq_t(), b.x.get_mpq_t());
  mpq_mul(tmp.get_mpq_t(), a[1].get_mpq_t(), b.y.get_mpq_t());
  mpq_add(out.get_mpq_t(), out.get_mpq_t(), tmp.get_mpq_t());
  mpq_mul(tmp.get_mpq_t(), a[2].get_mpq_t(), b.z.get_mpq_t());
  mpq_add(out.get_mpq_t(), out.get_mpq_t(), tmp.get_mpq_t());
}

// Fills s.ng with Ng = (v1-v0) x (v2-v0) = v0 x v1 + v1 x v2 + v2 x v0, and
// (when `d` is given) s.e[k] with d . (v_k x v_{k+1}).
void triangle_terms(const Triangle& tri, const ExactVec3* d, ExactScratch& s) {
  require_finite(tri.v0, "vertex");
  require_finite(tri.v1, "vertex");
  require_finite(tri.v2, "vertex");
  for (int a = 0; a < 3; ++a) s.ng[a] = 0;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      // float * float is exact in double (24 + 24 significant bits, no underflow).
      s.p = component(tri, k, b) * component(tri, k1, c);
      s.q = component(tri, k, c) * component(tri, k1, b);
      mpq_sub(s.vc[a].get_mpq_t(), s.p.get_mpq_t(), s.q.get_mpq_t());
      mpq_add(s.ng[a].get_mpq_t(), s.ng[a].get_mpq_t(), s.vc[a].get_mpq_t());
    }
    if (d) dot_into(s.e[k], s.vc, *d, s.p);
  }
}

// s.num = (v0 - o) . Ng, given s.ng.
void plane_numerator(const ExactVec3& o, const Triangle& tri, ExactScratch& s) {
  const ExactVec3 v0 = to_exact(tri.v0);
  mpq_sub(s.p.get_mpq_t(), v0.x.get_mpq_t(), o.x.get_mpq_t());
  mpq_mul(s.num.get_mpq_t(), s.p.get_mpq_t(), s.ng[0].get_mpq_t());
  mpq_sub(s.p.get_mpq_t(), v0.y.get_mpq_t(), o.y.get_mpq_t());
  mpq_mul(s.q.get_mpq_t(), s.p.get_mpq_t(), s.ng[1].get_mpq_t());
  mpq_add(s.num.get_mpq_t(), s.num.get_mpq_t(), s.q.get_mpq_t());
  mpq_sub(s.p.get_mpq_t(), v0.z.get_mpq_t(), o.z.get_mpq_t());
  mpq_mul(s.q.get_mpq_t(), s.p.get_mpq_t(), s.ng[2].get_mpq_t());
  mpq_add(s.num.get_mpq_t(), s.num.get_mpq_t(), s.q.get_mpq_t());
}

bool is_zero(const mpq_class* v) { return sgn(v[0]) == 0 && sgn(v[1]) == 0 && sgn(v[2]) == 0; }

}  // namespace

ExactVec3 to_exact(Vec3f v) {
  require_finite(v, "coordinate");
  // Every float is a double, and mpq_set_d is exact for finite doubles.
  return {mpq_class(static_cast<double>(v.x)), mpq_class(static_cast<double>(v.y)),
          mpq_class(static_cast<double>(v.z))};
}

// Edge functions e_k = d . ((v_k - o) x (v_{k+1} - o)), expanded as
// d . (v_k x v_{k+1}) + m . (v_{k+1} - v_k) with m = o x d, so that the
// origin's (possibly large) rationals enter only through m. Their sum is d . Ng.
ExactHit exact_intersect(const ExactRay& ray, const Triangle& tri) {
  ExactScratch& s = scratch;
  ExactHit hit;
  triangle_terms(tri, &ray.d, s);
  if (is_zero(s.ng)) return hit;  // degenerate triangle: never hit
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    mpq_mul(s.m[a].get_mpq_t(), component(ray.o, b).get_mpq_t(), component(ray.d, c).get_mpq_t());
    mpq_mul(s.p.get_mpq_t(), component(ray.o, c).get_mpq_t(), component(ray.d, b).get_mpq_t());
    mpq_sub(s.m[a].get_mpq_t(), s.m[a].get_mpq_t(), s.p.get_mpq_t());
  }
  const ExactVec3 v[3] = {to_exact(tri.v0), to_exact(tri.v1), to_exact(tri.v2)};
  for (int k = 0; k < 3; ++k) dot_into(s.mv[k], s.m, v[k], s.p);
  int positive = 0, negative = 0;
  for (int k = 0; k < 3; ++k) {
    mpq_add(s.e[k].get_mpq_t(), s.e[k].get_mpq_t(), s.mv[(k + 1) % 3].get_mpq_t());
    mpq_sub(s.e[k].get_mpq_t(), s.e[k].get_mpq_t(), s.mv[k].get_mpq_t());
    const int sign = sgn(s.e[k]);
    positive += sign > 0;
    negative += sign < 0;
    if (positive && negative) return hit;  // line passes outside the triangle
  }
  dot_into(s.den, s.ng, ray.d, s.p);
  if (sgn(s.den) == 0) return hit;  // plane contains the ray direction
  plane_numerator(ray.o, tri, s);
  if (sgn(s.num) == 0 || sgn(s.num) != sgn(s.den)) return hit;  // t <= 0
  mpq_div(s.num.get_mpq_t(), s.num.get_mpq_t(), s.den.get_mpq_t());
  if (ray.has_tmax && cmp(s.num, ray.tmax) >= 0) return hit;
  hit.hit = true;
  hit.t = s.num;
  return hit;
}

bool exact_degenerate(const Triangle& tri) {
  triangle_terms(tri, nullptr, scratch);
  return is_zero(scratch.ng);
}

bool exact_plane_crossing(const ExactRay& ray, const Triangle& tri, mpq_class& t) {
  ExactScratch& s = scratch;
  triangle_terms(tri, nullptr, s);
  dot_into(s.den, s.ng, ray.d, s.p);
  if (sgn(s.den) == 0) return false;
  plane_numerator(ray.o, tri, s);
  if (sgn(s.num) == 0 || sgn(s.num) != sgn(s.den)) return false;
  mpq_div(t.get_mpq_t(), s.num.get_mpq_t(), s.den.get_mpq_t());
  return !ray.has_tmax || cmp(t, ray.tmax) < 0;
}

bool exact_plane_point(Vec3f o, Vec3f d, const Triangle& tri, ExactVec3& out) {
  ExactScratch& s = scratch;
  const ExactVec3 eo = to_exact(o), ed = to_exact(d);
  triangle_terms(tri, nullptr, s);
  dot_into(s.den, s.ng, ed, s.p);
  if (sgn(s.den) == 0) return false;  // parallel (or degenerate triangle)
  plane_numerator(eo, tri, s);
  mpq_div(s.num.get_mpq_t(), s.num.get_mpq_t(), s.den.get_mpq_t());
  out.x = eo.x + s.num * ed.x;
  out.y = eo.y + s.num * ed.y;
  out.z = eo.z + s.num * ed.z;
  return true;
}

ExactVec3 exact_barycentric_point(const Triangle& tri, float u, float v) {
  if (!std::isfinite(u) || !std::isfinite(v))
    throw std::invalid_argument("exact geometry: non-finite barycentrics");
  const mpq_class eu(static_cast<double>(u)), ev(static_cast<double>(v));
  const mpq_class w = 1 - eu - ev;
  const ExactVec3 a = to_exact(tri.v0), b = to_exact(tri.v1), c = to_exact(tri.v2);
  return {w * a.x + eu * b.x + ev * c.x, w * a.y + eu * b.y + ev * c.y,
          w * a.z + eu * b.z + ev * c.z};
}

ExactVec3 exact_projection(Vec3f p, const Triangle& tri) {
  ExactScratch& s = scratch;
  const ExactVec3 ep = to_exact(p);
  triangle_terms(tri, nullptr, s);
  if (is_zero(s.ng)) throw std::invalid_argument("exact_projection: degenerate triangle");
  // p + ((v0 - p) . Ng / |Ng|^2) Ng
  plane_numerator(ep, tri, s);
  s.den = s.ng[0] * s.ng[0] + s.ng[1] * s.ng[1] + s.ng[2] * s.ng[2];
  s.num /= s.den;
  return {ep.x + s.num * s.ng[0], ep.y + s.num * s.ng[1], ep.z + s.num * s.ng[2]};
}

}  // namespace vbsim
