// Certified filter: every certain answer must equal the exact one. Rays are made
// adversarial (aimed at vertices and edges, nudged by one float ulp, with
// rational origins from plane points, at tiny and huge scales), so that the
// filter has to be both sound near zero and tight enough to decide most cases.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "exact/certified_filter.h"
#include "exact/exact_plane.h"
#include "exact/rational_rounding.h"
#include "oracle_test_support.h"

using namespace vbsim;

namespace {

Vec3f nudge(Vec3f p, std::mt19937& rng) {
  std::uniform_int_distribution<int> step(-1, 1);
  for (int a = 0; a < 3; ++a) {
    const int s = step(rng);
    if (s) p[a] = std::nextafter(p[a], s * INFINITY);
  }
  return p;
}

struct Counts {
  int miss = 0, hit = 0, plane_only = 0, unknown = 0;
};

// Checks one filter verdict against the reference; returns the verdict.
FilterVerdict check_pair(const ExactRay& ray, const FilterRay& fr, const Triangle& tri) {
  double lo = -1, hi = -1;
  const FilterVerdict v = filter_triangle(fr, tri, lo, hi);
  const ExactHit ref = test::reference_intersect(ray, tri);
  mpq_class t;
  switch (v) {
    case FilterVerdict::Miss:
      REQUIRE_FALSE(ref.hit);
      break;
    case FilterVerdict::Hit:
      REQUIRE(ref.hit);
      REQUIRE(lo <= ref.t);
      REQUIRE(ref.t <= hi);
      REQUIRE(lo >= 0);
      break;
    case FilterVerdict::PlaneOnly:
      REQUIRE(exact_plane_crossing(ray, tri, t) == ref.hit);
      if (ref.hit) REQUIRE(t == ref.t);
      break;
    case FilterVerdict::Unknown:
      break;
  }
  // The box of a hit triangle is never rejected up to the hit's t.
  if (ref.hit) {
    Bounds3f b;
    b.extend(tri.v0);
    b.extend(tri.v1);
    b.extend(tri.v2);
    const float lo3[3] = {b.lo.x, b.lo.y, b.lo.z}, hi3[3] = {b.hi.x, b.hi.y, b.hi.z};
    double near = -1;
    REQUIRE(filter_box(fr, lo3, hi3, round_up_double(ref.t), near));
    REQUIRE(near <= ref.t);
  }
  return v;
}

void count(Counts& c, FilterVerdict v) {
  c.miss += v == FilterVerdict::Miss;
  c.hit += v == FilterVerdict::Hit;
  c.plane_only += v == FilterVerdict::PlaneOnly;
  c.unknown += v == FilterVerdict::Unknown;
}

}  // namespace

TEST_CASE("certified filter agrees with rationals on adversarial rays", "[exact]") {
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> real(-1, 1);
  std::uniform_int_distribution<int> which(0, 5);
  for (const float scale : {1.0f, 0x1p-60f, 0x1p60f}) {
    Counts c;
    int certain_near_boundary = 0;
    auto rp = [&] { return scale * Vec3f{real(rng), real(rng), real(rng)}; };
    for (int i = 0; i < 1500; ++i) {
      const Triangle tri{rp(), rp(), rp()};
      const int w = which(rng);
      // Targets on the boundary (vertex, edge midpoint) or one ulp off it.
      Vec3f target = w == 0 ? tri.v0 : w == 1 ? 0.5f * (tri.v1 + tri.v2) : (1 / 3.0f) * (tri.v0 + tri.v1 + tri.v2);
      if (w >= 3) target = nudge(w == 3 ? tri.v2 : 0.5f * (tri.v0 + tri.v1), rng);
      ExactRay ray;
      if (i % 3 == 0) {
        // Rational origin: where a random ray meets the triangle's plane.
        const Vec3f po = rp(), pd = target - po + 0.1f * rp();
        if (!exact_plane_point(po, pd, tri, ray.o)) continue;
        ray.d = to_exact(rp());
      } else {
        const Vec3f o = 3.0f * rp();
        ray.o = to_exact(o);
        ray.d = to_exact(target - o);
      }
      if (i % 4 == 0) {
        ray.has_tmax = true;
        ray.tmax = 1;
      }
      const FilterRay fr = make_filter_ray(ray);
      REQUIRE(fr.usable);
      const FilterVerdict v = check_pair(ray, fr, tri);
      count(c, v);
      certain_near_boundary += w >= 3 && (v == FilterVerdict::Hit || v == FilterVerdict::Miss);
    }
    INFO("scale " << scale << ": miss " << c.miss << " hit " << c.hit << " plane_only " << c.plane_only
                  << " unknown " << c.unknown);
    // Tight enough: one-ulp-off rays are still decided in floating point.
    CHECK(certain_near_boundary > 300);
    CHECK(c.hit > 200);
    CHECK(c.unknown < 1000);
  }
}

TEST_CASE("certified filter: origins on the plane and exactly on edges are left to rationals", "[exact]") {
  const Triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  double lo, hi;
  ExactRay ray;
  ray.o = to_exact({0.25f, 0.25f, 0});
  ray.d = to_exact({0, 0, 1});
  CHECK(filter_triangle(make_filter_ray(ray), tri, lo, hi) == FilterVerdict::PlaneOnly);  // t = 0
  ray.o = to_exact({0.5f, 0.5f, 1});
  ray.d = to_exact({0, 0, -1});
  CHECK(filter_triangle(make_filter_ray(ray), tri, lo, hi) == FilterVerdict::Unknown);  // on an edge
  ray.o = to_exact({0.25f, 0.25f, 1});
  CHECK(filter_triangle(make_filter_ray(ray), tri, lo, hi) == FilterVerdict::Hit);
  CHECK(lo <= 1.0);
  CHECK(hi >= 1.0);
  CHECK((hi - lo) * 1e12 < 1.0);
  ray.o.x = mpq_class(1, 3);  // not a double: the filter works on an enclosure
  const FilterRay fr = make_filter_ray(ray);
  CHECK(fr.rd[0] > 0);
  CHECK(fr.o_lo[0] < ray.o.x);
  CHECK(fr.o_hi[0] > ray.o.x);
  CHECK(filter_triangle(fr, tri, lo, hi) == FilterVerdict::Hit);
  ray.d.x = mpq_class(1, 3);  // a direction that is not a double cannot be filtered
  CHECK_FALSE(make_filter_ray(ray).usable);
}
