// Shared material for the ray/triangle tester tests: hand-computed cases, a
// double-precision reference intersection, and deterministic random geometry.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "datapath/ray.h"
#include "datapath/triangle.h"

namespace vbsim::test {

/// A hit whose t, u, v, front were worked out by hand; every value is exact in float.
struct HandCase {
  const char* name;
  Triangle tri;
  Vec3f o, d;
  float t, u, v;
  uint8_t front;
};

inline std::vector<HandCase> hand_computed_cases() {
  const Triangle right{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};          // Ng = (0, 0, 1)
  const Triangle right_rotated{{1, 0, 0}, {0, 1, 0}, {0, 0, 0}};  // Ng = (0, 0, 1)
  // All rays meet the plane z = 0 at p = (0.25, 0.5, 0).
  return {
      // p = 0.25 v0 + 0.25 v1 + 0.5 v2; from +z, dot(d, Ng) = -1: front.
      {"straight down", right, {0.25f, 0.5f, 2}, {0, 0, -1}, 2.0f, 0.25f, 0.5f, 1},
      // From -z with |d| = 2: t = 3 / 2; dot(d, Ng) = 2: back.
      {"straight up", right, {0.25f, 0.5f, -3}, {0, 0, 2}, 1.5f, 0.25f, 0.5f, 0},
      // o + 2 d = (-0.75 + 1, 0 + 0.5, 4 - 4) = p.
      {"oblique", right, {-0.75f, 0, 4}, {0.5f, 0.25f, -2}, 2.0f, 0.25f, 0.5f, 1},
      // p = 0.25 v0 + 0.5 v1 + 0.25 v2 with the vertices rotated: u = 0.5, v = 0.25.
      {"rotated vertices", right_rotated, {0.25f, 0.5f, 2}, {0, 0, -1}, 2.0f, 0.5f, 0.25f, 1},
      // A triangle in the plane x = 3: Ng = (0,1,0) x (0,0,1) = (1,0,0).
      // p = (3, 0.25, 0.5) = 0.25 v0 + 0.25 v1 + 0.5 v2; d = (-2,0,0), t = 2.5.
      {"along -x", {{3, 0, 0}, {3, 1, 0}, {3, 0, 1}}, {8, 0.25f, 0.5f}, {-2, 0, 0}, 2.5f, 0.25f,
       0.5f, 1},
      // Same triangle from x = -1 along +y and +x: o + 4 d = (3, 0.25, 0.5); back.
      {"oblique from behind", {{3, 0, 0}, {3, 1, 0}, {3, 0, 1}}, {-1, -0.75f, 0.5f},
       {1, 0.25f, 0}, 4.0f, 0.25f, 0.5f, 0},
  };
}

/// Intersection in double precision from the float inputs (Cramer's rule), with
/// how well-conditioned the float answer should be.
struct ReferenceHit {
  bool hit = false;
  double t = 0, u = 0, v = 0;
  double cosine = 0;           ///< cos of the angle between d and Ng
  double edge_distance = 0;    ///< min |barycentric|: distance from the nearest edge line
};

inline ReferenceHit reference_intersect(const Triangle& tri, Vec3f of, Vec3f df) {
  const double v0[3] = {tri.v0.x, tri.v0.y, tri.v0.z};
  const double v1[3] = {tri.v1.x, tri.v1.y, tri.v1.z};
  const double v2[3] = {tri.v2.x, tri.v2.y, tri.v2.z};
  const double o[3] = {of.x, of.y, of.z}, d[3] = {df.x, df.y, df.z};
  double e1[3], e2[3], s[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = v1[i] - v0[i];
    e2[i] = v2[i] - v0[i];
    s[i] = o[i] - v0[i];
  }
  auto cross = [](const double* a, const double* b, double* out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
  };
  auto dot = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  double n[3], p[3], q[3];
  cross(e1, e2, n);
  cross(d, e2, p);
  cross(s, e1, q);
  ReferenceHit r;
  r.cosine = dot(d, n) / std::sqrt(dot(d, d) * dot(n, n));
  const double det = dot(e1, p);
  if (det == 0.0) return r;
  r.u = dot(s, p) / det;
  r.v = dot(d, q) / det;
  r.t = dot(e2, q) / det;
  const double w = 1.0 - r.u - r.v;
  r.edge_distance = std::min({std::fabs(w), std::fabs(r.u), std::fabs(r.v)});
  r.hit = w >= 0 && r.u >= 0 && r.v >= 0 && r.t > 0;
  return r;
}

/// dot(d, Ng) in double from the float vertices: the trace spec's front bit is (this < 0).
inline double reference_facing(const Triangle& tri, Vec3f d) {
  const double e1[3] = {double(tri.v1.x) - tri.v0.x, double(tri.v1.y) - tri.v0.y,
                        double(tri.v1.z) - tri.v0.z};
  const double e2[3] = {double(tri.v2.x) - tri.v0.x, double(tri.v2.y) - tri.v0.y,
                        double(tri.v2.z) - tri.v0.z};
  return d.x * (e1[1] * e2[2] - e1[2] * e2[1]) + d.y * (e1[2] * e2[0] - e1[0] * e2[2]) +
         d.z * (e1[0] * e2[1] - e1[1] * e2[0]);
}

/// Deterministic random triangles and rays (mt19937 raw bits, no <random> distributions).
class RandomGeometry {
 public:
  explicit RandomGeometry(uint32_t seed) : gen_(seed) {}
  /// Uniform in [lo, hi), rounded to float.
  float uniform(double lo, double hi) {
    return static_cast<float>(lo + (hi - lo) * ((gen_() >> 8) * (1.0 / 16777216.0)));
  }
  Vec3f point(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
  /// A triangle in [-1, 1]^3 that is not close to degenerate.
  Triangle triangle() {
    for (;;) {
      const Triangle tri{point(-1, 1), point(-1, 1), point(-1, 1)};
      const Vec3f e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
      if (length(cross(e1, e2)) > 0.1f * length(e1) * length(e2)) return tri;
    }
  }
  /// A ray from a random origin in [-4, 4]^3 towards the plane point with
  /// barycentrics (1-b1-b2, b1, b2), b1, b2 in [-0.25, 1.25); |d| scaled by 2^[-3, 3].
  void ray_towards(const Triangle& tri, Vec3f& o, Vec3f& d) {
    o = point(-4, 4);
    const double b1 = uniform(-0.25, 1.25), b2 = uniform(-0.25, 1.25), b0 = 1.0 - b1 - b2;
    const double scale = std::ldexp(1.0, static_cast<int>(gen_() % 7) - 3);
    for (int i = 0; i < 3; ++i) {
      const double target = b0 * tri.v0[i] + b1 * tri.v1[i] + b2 * tri.v2[i];
      d[i] = static_cast<float>((target - o[i]) * scale);
    }
  }

 private:
  std::mt19937 gen_;
};

/// Two triangles of the tessellated box placed at 1000.37 (make_tessellated_box(8,
/// {2.5, 1000.37, 1000.37, 1000.37})) that share the edge lo-hi, and a ray from one
/// of the standard outside origins aimed at the exact midpoint of that edge. d is
/// exactly target - o, so the ray passes exactly through the edge at t = 1, crossing
/// both triangles' plane at cos(d, Ng) = 0.56. Found by the watertightness search:
/// float Möller–Trumbore misses both triangles.
struct SharedEdgeCase {
  Triangle first, second;
  Vec3f lo, hi;  ///< the shared edge
  Vec3f target;  ///< its midpoint
  Vec3f o, d;
};

inline SharedEdgeCase translated_box_shared_edge() {
  const float c = 0x1.f2ef5cp+9f;  // 997.869995: box corner coordinate
  const float f = 0x1.f33f5cp+9f;  // 998.494995: one grid step (0.625) further
  SharedEdgeCase e;
  e.lo = {c, c, c};
  e.hi = {c, f, f};
  e.first = {{c, c, c}, {c, f, f}, {c, f, c}};
  e.second = {{c, c, c}, {c, c, f}, {c, f, f}};
  e.target = {c, 0x1.f3175cp+9f, 0x1.f3175cp+9f};
  e.o = {0x1.f43268p+9f, 0x1.f46abep+9f, 0x1.f46682p+9f};
  e.d = {-0x1.430cp+1f, -0x1.5362p+1f, -0x1.4f26p+1f};
  return e;
}

}  // namespace vbsim::test
