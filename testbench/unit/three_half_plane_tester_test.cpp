// The three-half-plane tester: the intersect() contract, its front/back bit,
// agreement with a double-precision reference, and its watertight details.
#include <catch2/catch.hpp>

#include <cmath>

#include "datapath/testers.h"
#include "tester_contract_checks.h"
#include "tester_test_support.h"

namespace vbsim {
namespace {

using test::kInf;
using test::shoot;

TEST_CASE("three-half-plane: hand-computed hits give exact t, u, v and front", "[tester]") {
  test::check_hand_computed_hits<ThreeHalfPlaneTester>();
}

TEST_CASE("three-half-plane: rays just outside each edge miss, just inside hit", "[tester]") {
  test::check_edges_and_outside<ThreeHalfPlaneTester>();
}

TEST_CASE("three-half-plane: tmin and tmax are open ends", "[tester]") {
  test::check_open_interval<ThreeHalfPlaneTester>();
}

TEST_CASE("three-half-plane: a ray in the triangle's plane is not hit", "[tester]") {
  test::check_rays_in_plane<ThreeHalfPlaneTester>();
}

TEST_CASE("three-half-plane: front bit is dot(d, Ng) < 0 on random rays from both sides",
          "[tester]") {
  // Checks the derivation in three_half_plane_tester.cpp: det > 0 <=> dot(d, Ng) < 0,
  // for every (kz, sign of d[kz]) combination the random directions produce.
  test::check_front_bit_on_random_rays<ThreeHalfPlaneTester>(31);
}

TEST_CASE("three-half-plane: agrees with a double-precision reference on well-conditioned rays",
          "[tester]") {
  test::check_agreement_with_reference<ThreeHalfPlaneTester>(32);
}

TEST_CASE("three-half-plane: front bit for every dominant axis and direction sign", "[tester]") {
  // Triangle in the plane x + y + z = 1, Ng = (1,1,1) x ... = (1, 1, 1) up to scale.
  const Triangle tri{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Vec3f centre{0.25f, 0.25f, 0.5f};  // on the plane, inside the triangle
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {1.0f, -1.0f}) {
      Vec3f d{0.25f, 0.125f, 0.375f};
      d[axis] = 2.0f * sign;  // axis dominates
      const Vec3f o = centre - d;
      Hit hit;
      INFO("dominant axis " << axis << " sign " << sign);
      REQUIRE(shoot<ThreeHalfPlaneTester>(tri, o, d, hit));
      CHECK(hit.t == Approx(1.0f).epsilon(1e-6));
      CHECK(int(hit.front) == (test::reference_facing(tri, d) < 0 ? 1 : 0));
    }
  }
}

// A ray 2^-25 outside edge BC: in float the two products of that edge function
// round to the same value (-1), so the float edge function is exactly zero; the
// double redo finds its true sign. The triangle on the far side of the edge is
// missed and its neighbour across BC is hit, exactly one of the two.
TEST_CASE("three-half-plane: a zero edge function is decided in double", "[tester]") {
  const float eps23 = std::ldexp(1.0f, -23), eps24 = std::ldexp(1.0f, -24);
  const Vec3f a{1, -1, 1}, b{1 + eps23, 1, 1}, c{-1, -1 + eps24, 1}, d_vertex{-1, 1, 1};
  // Float products of edge B->C seen from the origin: cx*by = -1, cy*bx rounds to -1.
  REQUIRE(c.x * b.y == -1.0f);
  REQUIRE(c.y * b.x == -1.0f);
  REQUIRE(double(c.y) * double(b.x) != -1.0);

  const Triangle far_side{a, b, c};          // true U = 2^-24 - 2^-47 > 0, V, W < 0: miss
  const Triangle near_side{c, b, d_vertex};  // shares B, C; all three edge functions < 0
  const Vec3f o{0, 0, 0}, up{0, 0, 1};
  Hit hit;
  CHECK_FALSE(shoot<ThreeHalfPlaneTester>(far_side, o, up, hit));
  REQUIRE(shoot<ThreeHalfPlaneTester>(near_side, o, up, hit));
  CHECK(hit.t == 1.0f);
  CHECK(int(hit.front) == (test::reference_facing(near_side, up) < 0 ? 1 : 0));
}

TEST_CASE("three-half-plane: an exact ray through a shared edge hits (translated box)",
          "[tester]") {
  const test::SharedEdgeCase c = test::translated_box_shared_edge();
  Hit first, second;
  const bool hit_first = shoot<ThreeHalfPlaneTester>(c.first, c.o, c.d, first);
  const bool hit_second = shoot<ThreeHalfPlaneTester>(c.second, c.o, c.d, second);
  CHECK((hit_first || hit_second));
  if (hit_first) CHECK(first.t == Approx(1.0f).epsilon(1e-6));
  if (hit_second) CHECK(second.t == Approx(1.0f).epsilon(1e-6));
}

}  // namespace
}  // namespace vbsim
