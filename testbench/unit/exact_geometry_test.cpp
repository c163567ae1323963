// Exact geometry: float-to-rational conversion, the rational ray/triangle test
// (hand-computed cases and a cross-check against Cramer's rule), the exact
// points intended origins are built from, and correct rounding to double.
#include <catch2/catch.hpp>

#include <cfloat>
#include <cmath>
#include <random>

#include "exact/exact_geometry.h"
#include "exact/exact_plane.h"
#include "exact/rational_rounding.h"
#include "oracle_test_support.h"

using namespace vbsim;

namespace {

ExactRay make_ray(Vec3f o, Vec3f d) {
  ExactRay r;
  r.o = to_exact(o);
  r.d = to_exact(d);
  return r;
}

mpq_class plane_offset(const ExactVec3& p, const Triangle& tri) {
  const ExactVec3 v0 = to_exact(tri.v0);
  const ExactVec3 e1 = test::sub(to_exact(tri.v1), v0), e2 = test::sub(to_exact(tri.v2), v0);
  return test::det3(test::sub(p, v0), e1, e2);  // (p - v0) . (e1 x e2)
}

const Triangle kUnit{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // Ng = +z

}  // namespace

TEST_CASE("to_exact converts floats without rounding", "[exact]") {
  const ExactVec3 v = to_exact({0.1f, -3.0f, 1e-45f});
  CHECK(v.x == mpq_class(13421773, 134217728));  // 0.1f = 13421773 / 2^27
  CHECK(v.y == -3);
  mpq_class tiny(1);
  tiny /= mpq_class(mpz_class(1) << 149);  // smallest subnormal float
  CHECK(v.z == tiny);
  CHECK_THROWS(to_exact({NAN, 0, 0}));
  const Triangle bad{{INFINITY, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  ExactRay r;
  r.o = to_exact({0, 0, 1});
  r.d = to_exact({0, 0, -1});
  CHECK_THROWS_AS(exact_intersect(r, bad), std::invalid_argument);
}

TEST_CASE("exact_intersect: hand-computed hits and misses", "[exact]") {
  SECTION("perpendicular hit at t = 3/2") {
    const ExactHit h = exact_intersect(make_ray({0.25f, 0.25f, 3}, {0, 0, -2}), kUnit);
    REQUIRE(h.hit);
    CHECK(h.t == mpq_class(3, 2));
  }
  SECTION("both faces are hit") {
    const ExactHit h = exact_intersect(make_ray({0.25f, 0.25f, -1}, {0, 0, 4}), kUnit);
    REQUIRE(h.hit);
    CHECK(h.t == mpq_class(1, 4));
  }
  SECTION("the boundary is part of the triangle: edge and vertex") {
    CHECK(exact_intersect(make_ray({0.5f, 0.5f, 1}, {0, 0, -1}), kUnit).hit);  // hypotenuse
    CHECK(exact_intersect(make_ray({1, 0, 1}, {0, 0, -1}), kUnit).hit);        // vertex v1
    CHECK_FALSE(exact_intersect(make_ray({0.5f, 0.5000001f, 1}, {0, 0, -1}), kUnit).hit);
  }
  SECTION("a ray in the triangle's plane does not hit it") {
    CHECK_FALSE(exact_intersect(make_ray({-1, 0.25f, 0}, {1, 0, 0}), kUnit).hit);
  }
  SECTION("the interval is open at 0 and at tmax") {
    CHECK_FALSE(exact_intersect(make_ray({0.25f, 0.25f, 0}, {0, 0, 1}), kUnit).hit);  // t = 0
    ExactRay r = make_ray({0.25f, 0.25f, 2}, {0, 0, -1});
    r.has_tmax = true;
    r.tmax = 2;
    CHECK_FALSE(exact_intersect(r, kUnit).hit);
    r.tmax = mpq_class(2) + mpq_class(1, 1000000);
    CHECK(exact_intersect(r, kUnit).hit);
    CHECK_FALSE(exact_intersect(make_ray({0.25f, 0.25f, 2}, {0, 0, 1}), kUnit).hit);  // behind
  }
  SECTION("a degenerate triangle is never hit") {
    const Triangle line{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}};
    CHECK(exact_degenerate(line));
    CHECK_FALSE(exact_degenerate(kUnit));
    CHECK_FALSE(exact_intersect(make_ray({1, 1, 1}, {0, 0, -1}), line).hit);
  }
}

TEST_CASE("exact_intersect agrees with Cramer's rule on grid and random rays", "[exact]") {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> grid(-3, 3);
  std::uniform_real_distribution<float> real(-2, 2);
  auto grid_point = [&] { return Vec3f{grid(rng) * 0.5f, grid(rng) * 0.5f, grid(rng) * 0.5f}; };
  int hits = 0, boundary = 0;
  for (int i = 0; i < 3000; ++i) {
    const bool on_grid = i % 2 == 0;
    const Triangle tri = on_grid ? Triangle{grid_point(), grid_point(), grid_point()}
                                 : Triangle{{real(rng), real(rng), real(rng)},
                                            {real(rng), real(rng), real(rng)},
                                            {real(rng), real(rng), real(rng)}};
    // Aim grid rays at a vertex or an edge midpoint (exact in float) half the time.
    const Vec3f o = on_grid ? grid_point() : Vec3f{real(rng), real(rng), real(rng)};
    Vec3f target = grid_point();
    if (i % 4 == 0) target = tri.v0;
    if (i % 4 == 2) target = 0.5f * (tri.v1 + tri.v2);
    Vec3f d = target - o;
    if (d == Vec3f{}) d = {0, 0, 1};
    ExactRay r = make_ray(o, d);
    if (i % 3 == 0) {
      r.has_tmax = true;
      r.tmax = 1;  // a shadow ray to the target: the target itself excluded
    }
    const ExactHit a = exact_intersect(r, tri), b = test::reference_intersect(r, tri);
    REQUIRE(a.hit == b.hit);
    if (a.hit) {
      REQUIRE(a.t == b.t);
      ++hits;
      boundary += i % 4 != 1 && i % 4 != 3;
    }
  }
  CHECK(hits > 300);
  CHECK(boundary > 100);
}

TEST_CASE("exact points: plane point, barycentric point, projection", "[exact]") {
  const Triangle tri{{0.1f, 0.2f, 0.3f}, {1.3f, 0.1f, 0.7f}, {0.3f, 1.1f, -0.4f}};
  SECTION("plane point lies on the plane and on the ray") {
    const Vec3f o{0.3f, -0.7f, 2.1f}, d{0.1f, 0.9f, -1.7f};
    ExactVec3 p;
    REQUIRE(exact_plane_point(o, d, tri, p));
    CHECK(plane_offset(p, tri) == 0);
    const ExactVec3 op = test::sub(p, to_exact(o)), ed = to_exact(d);
    CHECK(op.x * ed.y - op.y * ed.x == 0);  // (p - o) parallel to d
    CHECK(op.y * ed.z - op.z * ed.y == 0);
    CHECK(plane_offset(to_exact(o), tri) != 0);
  }
  SECTION("parallel direction has no plane point") {
    ExactVec3 p;
    CHECK_FALSE(exact_plane_point({0, 0, 5}, {1, 2, 0}, kUnit, p));
  }
  SECTION("barycentric point") {
    const ExactVec3 p = exact_barycentric_point(tri, 0.25f, 0.5f);
    const ExactVec3 a = to_exact(tri.v0), b = to_exact(tri.v1), c = to_exact(tri.v2);
    CHECK(p.x == (a.x + b.x + 2 * c.x) / 4);
    CHECK(p.z == (a.z + b.z + 2 * c.z) / 4);
    CHECK(plane_offset(p, tri) == 0);
  }
  SECTION("projection is on the plane along the normal") {
    const Vec3f o{0.5f, 0.5f, 1.25f};
    const ExactVec3 p = exact_projection(o, tri);
    CHECK(plane_offset(p, tri) == 0);
    const ExactVec3 po = test::sub(to_exact(o), p);
    // po is orthogonal to both edges
    const ExactVec3 e1 = test::sub(to_exact(tri.v1), to_exact(tri.v0));
    const ExactVec3 e2 = test::sub(to_exact(tri.v2), to_exact(tri.v0));
    CHECK(po.x * e1.x + po.y * e1.y + po.z * e1.z == 0);
    CHECK(po.x * e2.x + po.y * e2.y + po.z * e2.z == 0);
    CHECK_FALSE(po.x == 0);
  }
}

TEST_CASE("round_to_nearest_double rounds like IEEE division", "[exact]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> mant(0.5, 1.0);
  std::uniform_int_distribution<int> ex(-1060, 1000);
  for (int i = 0; i < 2000; ++i) {
    const double a = std::ldexp(mant(rng), ex(rng) / 2), b = std::ldexp(mant(rng), -ex(rng) / 2);
    const double sign = i % 2 ? -1.0 : 1.0;
    const mpq_class q = mpq_class(sign * a) / mpq_class(b);
    REQUIRE(round_to_nearest_double(q) == sign * a / b);  // IEEE division is correctly rounded
    REQUIRE(round_down_double(q) <= q);
    REQUIRE(round_up_double(q) >= q);
    REQUIRE(std::nextafter(round_down_double(q), INFINITY) >= round_up_double(q));
  }
  // Exact midpoints go to the even neighbour.
  const mpq_class ulp_half(mpq_class(1) / mpq_class(mpz_class(1) << 53));
  CHECK(round_to_nearest_double(1 + ulp_half) == 1.0);
  CHECK(round_to_nearest_double(1 + 3 * ulp_half) == 1.0 + 0x1p-51);
  CHECK(round_to_nearest_double(mpq_class(1, 3)) == 1.0 / 3.0);
  CHECK(round_to_nearest_double(mpq_class(DBL_MAX) * 2) == INFINITY);
}
