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
  bool intersect(const Triangle& tri, float tmax, Hit& hit) const { return test<false>(tri, tmax, hit); }

 protected:
  /// The test; with kConservativeT, also pbrt-v4's check that t exceeds the
  /// bound of its own rounding error (PbrtWatertightTester).
  template <bool kConservativeT>
  bool test(const Triangle& tri, float tmax, Hit& hit) const;

 private:
  Vec3f o_;
  float tmin_;
  int kx_, ky_, kz_;
  float sx_, sy_, sz_;
};

/// pbrt-v4's triangle test: the same watertight evaluation, plus its
/// conservative check that the computed t is larger than a bound of its own
/// rounding error (t <= deltaT is no hit), which pbrt's error-bound origin offset
/// relies on. Same front bit and barycentrics as ThreeHalfPlaneTester.
class PbrtWatertightTester : public ThreeHalfPlaneTester {
 public:
  explicit PbrtWatertightTester(const Ray& ray) : ThreeHalfPlaneTester(ray) {}
  bool intersect(const Triangle& tri, float tmax, Hit& hit) const { return test<true>(tri, tmax, hit); }
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
