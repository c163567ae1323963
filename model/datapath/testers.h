// Ray/triangle testers. Each is constructed once per ray (per-ray set-up, as a
// hardware tester latches the ray) and then tests triangles.
//
// Contract of intersect(): true when the ray meets the triangle at tmin < t < tmax
// (tmin from the ray, tmax passed in so a closest-hit search can shrink it); on
// true it fills hit.t, hit.u, hit.v (p = (1-u-v) v0 + u v1 + v v2) and hit.front
// (1 when dot(d, Ng) < 0), and leaves hit.prim alone. Both faces are tested
// (no culling). A triangle whose plane contains the ray is not hit.
#pragma once
#include <cmath>
#include <string>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "datapath/hit.h"
#include "datapath/ray.h"
#include "datapath/triangle.h"

namespace vbsim {

class TriangleLanes;

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
  explicit ThreeHalfPlaneTester(const Ray& ray);  ///< the per-ray set-up (inline, below)
  bool intersect(const Triangle& tri, float tmax, Hit& hit) const;

#if defined(__SSE2__)  // the four-lane form (a search looks for LaneHits: search_rules.h)
  /// What intersect_lanes answers for up to four triangles (lanes 0..3).
  struct LaneHits {
    /// Bit l: triangle l passes every check intersect(triangle l, bound) makes
    /// before its division (the edge signs, det != 0, the scaled interval); its
    /// other fields are valid. below() makes the rest.
    unsigned met = 0;
    unsigned redo = 0;  ///< bit l: an edge function came out exactly 0: ask intersect() itself
    alignas(16) float t_scaled[4], e_v[4], e_w[4], det[4];
    float tmin = 0;  ///< the ray's tmin
    /// For a lane of `met` and `tmax` <= the bound: intersect(triangle l, tmax)'s
    /// answer (its scaled upper check with `tmax`, then t = t_scaled / det
    /// inside (tmin, tmax)). The division is left to a lane that gets this far
    /// (one in several), off the vector pass's dependency chain.
    bool below(int l, float tmax) const {
      const float abs_det = std::fabs(det[l]), t_signed = det[l] < 0.0f ? -t_scaled[l] : t_scaled[l];
      const float t = t_scaled[l] / det[l];
      return t_signed < tmax * abs_det && t > tmin && t < tmax;
    }
    /// intersect()'s hit for a lane of `met` that below() passed.
    Hit hit(int l) const {
      Hit h;
      h.t = t_scaled[l] / det[l];
      h.u = e_v[l] / det[l];
      h.v = e_w[l] / det[l];
      h.front = det[l] > 0.0f ? 1 : 0;
      return h;
    }
  };
  /// intersect() of the triangles first .. first + n - 1 (1 <= n <= 4) of
  /// `lanes` against the interval (tmin, bound), four lanes in one SSE2 pass
  /// with the same float operations in the same order (so the same bits).
  /// A lane whose edge functions need intersect()'s double-precision redo is
  /// only flagged. Defined in three_half_plane_lanes.h.
  void intersect_lanes(const TriangleLanes& lanes, uint32_t first, int n, float bound, LaneHits& out) const;
#endif

 private:
  Vec3f o_;
  float tmin_;
  int kx_, ky_, kz_;
  float sx_, sy_, sz_;
};

// The set-up: the axis the direction is longest along becomes z (kz), the
// other two follow in cyclic order (swapped when d[kz] < 0, which keeps the
// projection's winding), and the shear maps d to +z (the .cpp's derivation).
inline ThreeHalfPlaneTester::ThreeHalfPlaneTester(const Ray& ray) : o_(ray.o), tmin_(ray.tmin) {
  static constexpr int kNext[3] = {1, 2, 0};
  const float d[3] = {ray.d.x, ray.d.y, ray.d.z};
  kz_ = max_dimension(ray.d);
  const int next = kNext[kz_], after = kNext[next];
  const bool flip = d[kz_] < 0.0f;  // swapped: keeps the winding of the projection
  kx_ = flip ? after : next;
  ky_ = flip ? next : after;
#if defined(__SSE2__)
  // The three quotients in one vector division (each lane rounds as its own division would).
  alignas(16) float q[4];
  _mm_store_ps(q, _mm_div_ps(_mm_setr_ps(d[kx_], d[ky_], 1.0f, 1.0f), _mm_set1_ps(d[kz_])));
  sx_ = q[0];
  sy_ = q[1];
  sz_ = q[2];
#else
  sx_ = d[kx_] / d[kz_];
  sy_ = d[ky_] / d[kz_];
  sz_ = 1.0f / d[kz_];
#endif
}

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
