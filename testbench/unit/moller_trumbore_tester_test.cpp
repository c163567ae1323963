// The float32 Möller–Trumbore tester: the intersect() contract, its front/back
// bit, agreement with a double-precision reference, and a recorded hole.
#include <catch2/catch.hpp>

#include <cmath>

#include "datapath/testers.h"
#include "tester_contract_checks.h"
#include "tester_test_support.h"

namespace vbsim {
namespace {

using test::shoot;

TEST_CASE("moller-trumbore: hand-computed hits give exact t, u, v and front", "[tester]") {
  test::check_hand_computed_hits<MollerTrumboreTester>();
}

TEST_CASE("moller-trumbore: rays just outside each edge miss, just inside hit", "[tester]") {
  test::check_edges_and_outside<MollerTrumboreTester>();
}

TEST_CASE("moller-trumbore: tmin and tmax are open ends", "[tester]") {
  test::check_open_interval<MollerTrumboreTester>();
}

TEST_CASE("moller-trumbore: a ray in the triangle's plane is not hit", "[tester]") {
  test::check_rays_in_plane<MollerTrumboreTester>();
}

TEST_CASE("moller-trumbore: front bit is dot(d, Ng) < 0 on random rays from both sides",
          "[tester]") {
  // Checks det = e1 . (d x e2) = -dot(d, Ng) (moller_trumbore_tester.cpp).
  test::check_front_bit_on_random_rays<MollerTrumboreTester>(41);
}

TEST_CASE("moller-trumbore: agrees with a double-precision reference on well-conditioned rays",
          "[tester]") {
  test::check_agreement_with_reference<MollerTrumboreTester>(42);
}

TEST_CASE("moller-trumbore: only det == 0 is rejected, a nearly parallel ray still hits",
          "[tester]") {
  // d . Ng = -2^-20: det = 2^-20. o + d = (0.25, 0.25, 0).
  const Triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const float tiny = std::ldexp(1.0f, -20);
  Hit hit;
  REQUIRE(shoot<MollerTrumboreTester>(tri, {-0.75f, 0.25f, tiny}, {1, 0, -tiny}, hit));
  CHECK(hit.t == 1.0f);
  CHECK(hit.u == 0.25f);
  CHECK(hit.v == 0.25f);
  CHECK(hit.front == 1);
}

TEST_CASE("moller-trumbore: misses both triangles of an exact ray through their shared edge",
          "[tester]") {
  // A regression record of the non-watertightness the measurement counts.
  const test::SharedEdgeCase c = test::translated_box_shared_edge();
  // The data is what it claims: the target is the exact midpoint of the shared
  // edge, the ray passes exactly through it at t = 1, and the edge is shared.
  for (int i = 0; i < 3; ++i) {
    CHECK(2.0 * double(c.target[i]) == double(c.lo[i]) + double(c.hi[i]));
    CHECK(double(c.o[i]) + double(c.d[i]) == double(c.target[i]));
  }
  CHECK(c.first.v0 == c.lo);
  CHECK(c.first.v1 == c.hi);
  CHECK(c.second.v0 == c.lo);
  CHECK(c.second.v2 == c.hi);
  // Both planes are crossed from the same side, well away from grazing.
  const double f1 = test::reference_facing(c.first, c.d), f2 = test::reference_facing(c.second, c.d);
  CHECK(f1 * f2 > 0.0);

  Hit hit;
  CHECK_FALSE(shoot<MollerTrumboreTester>(c.first, c.o, c.d, hit));
  CHECK_FALSE(shoot<MollerTrumboreTester>(c.second, c.o, c.d, hit));
}

}  // namespace
}  // namespace vbsim
