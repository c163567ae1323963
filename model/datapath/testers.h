// Ray/triangle testers. Each is constructed once per ray (per-ray set-up, as a
// hardware tester latches the ray) and then tests triangles.
//
// Contract of intersect(): true when the ray meets the triangle at tmin < t < tmax
// (tmin from the ray, tmax passed in so a closest-hit search can shrink it); on
// true it fills hit.t, hit.u, hit.v (p = (1-u-v) v0 + u v1 + v v2) and hit.front
// (1 when dot(d, Ng) < 0), and leaves hit.prim alone. Both faces are tested
// (no culling). A triangle whose plane contains the ray is not hit.
#pragma once
#include <string>

#include "datapath/hit.h"
#include "datapath/ray.h"
#include "datapath/triangle.h"

namespace vbsim {

enum class TesterKind { ThreeHalfPlane, MollerTrumbore, PbrtWatertight };
/// "three-half-plane" / "moller-trumbore" / "pbrt-watertight"
const char* tester_name(TesterKind kind);
bool parse_tester(const std::string& name, TesterKind& out);

/// The patent's three-half-plane test: the ray hits when its direction lies on
/// the same side of the three planes through the ray origin and each edge; that
/// common side is the front/back bit. Watertight: evaluated in a sheared ray
/// space (Woop, Benthin, Wald 2013) with a double-precision redo of any edge
/// function that is exactly zero, so a ray through a shared edge or vertex of a
/// closed mesh hits at least one of the triangles.
class ThreeHalfPlaneTester {
 public:
  explicit ThreeHalfPlaneTester(const Ray& ray);
  bool intersect(const Triangle& tri, float tmax, Hit& hit) const;

 private:
  Vec3f o_;
  float tmin_;
  int kx_, ky_, kz_;
  float sx_, sy_, sz_;
};

/// What pbrt-v4's IntersectTriangle returns: barycentrics b0, b1, b2 (weights
/// of v0, v1, v2, each e_i / det computed as e_i * (1 / det)) and t; front as
/// in Hit (the side pbrt's det sign tells, which pbrt itself does not report).
struct PbrtTriangleHit {
  float b0 = 0, b1 = 0, b2 = 0, t = 0;
  bool front = false;
};

/// pbrt-v4's triangle test (shapes.cpp IntersectTriangle) in its own float32
/// arithmetic: the same watertight sheared evaluation, but with the edge
/// functions as FMA differences of products, no axis swap, t and the
/// barycentrics multiplied by 1 / det, and its conservative check that t
/// exceeds a bound of its own rounding error (t <= deltaT is no hit), which
/// pbrt's error-bound origin offset relies on. docs/testers.md lists what the
/// contract adds on top (open interval, tmin).
class PbrtWatertightTester {
 public:
  explicit PbrtWatertightTester(const Ray& ray);
  /// The tester contract above: pbrt's answer, kept only when tmin < t < tmax.
  bool intersect(const Triangle& tri, float tmax, Hit& hit) const;
  /// pbrt-v4's IntersectTriangle(ray, tmax, v0, v1, v2) as it is (no tmin,
  /// t <= tmax allowed); false also where pbrt would return a NaN t.
  bool intersect_triangle(const Triangle& tri, float tmax, PbrtTriangleHit& out) const;

 private:
  Vec3f o_;
  float tmin_;
  int kx_, ky_, kz_;
  float sx_, sy_, sz_;
  bool dz_negative_;  ///< d[kz] < 0: front is det > 0 exactly then (see the .cpp)
};

/// Möller–Trumbore (1997) in float32, as the renderer blog writes it, without
/// culling: not watertight.
class MollerTrumboreTester {
 public:
  explicit MollerTrumboreTester(const Ray& ray);
  bool intersect(const Triangle& tri, float tmax, Hit& hit) const;

 private:
  Vec3f o_, d_;
  float tmin_;
};

}  // namespace vbsim
