// The rounding helpers of datapath/reduced_precision.h, on values worked out by hand.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "datapath/reduced_precision.h"

using namespace vbsim;

TEST_CASE("directed rounding to fewer fraction bits goes toward -inf and +inf", "[datapath][precision]") {
  const float above_one = 1.0f + std::ldexp(1.0f, -23);  // 1 + 1 ulp
  CHECK(round_down(above_one, 0) == 1.0f);
  CHECK(round_up(above_one, 0) == 2.0f);
  CHECK(round_down(-above_one, 0) == -2.0f);
  CHECK(round_up(-above_one, 0) == -1.0f);
  // 1.375 = 1.011b: two fraction bits give 1.25 below and 1.5 above.
  CHECK(round_down(1.375f, 2) == 1.25f);
  CHECK(round_up(1.375f, 2) == 1.5f);
  CHECK(round_up(1.375f, 3) == 1.375f);  // representable: unchanged
  // A carry into the exponent: 1.9375 = 1.1111b up with two bits is 2.
  CHECK(round_up(1.9375f, 2) == 2.0f);
  CHECK(round_down(0.0f, 0) == 0.0f);
  CHECK(round_up(above_one, 23) == above_one);
  const float inf = std::numeric_limits<float>::infinity();
  CHECK(round_down(inf, 4) == inf);
  CHECK(round_up(-inf, 4) == -inf);
}

TEST_CASE("rounding to nearest with fewer fraction bits breaks ties to even", "[datapath][precision]") {
  CHECK(round_nearest(1.75f, 1) == 2.0f);   // 1.11b: halfway between 1.1b and 10.0b; 10.0b is even
  CHECK(round_nearest(1.25f, 1) == 1.0f);   // 1.01b: halfway between 1.0b (even) and 1.1b
  CHECK(round_nearest(1.3f, 1) == 1.5f);    // nearer 1.5
  CHECK(round_nearest(-1.3f, 1) == -1.5f);
  CHECK(round_nearest(1.3f, 23) == 1.3f);
}

TEST_CASE("a box rounded outward contains the original", "[datapath][precision]") {
  BvhNode n;
  Bounds3f b;
  b.lo = {-1.3f, 0.3f, 2.7f};
  b.hi = {-0.3f, 1.3f, 3.1f};
  n.set_child(0, b, {0, 1});
  n.set_child(1, b, {1, 1});
  for (int bits : {0, 3, 10, 23}) {
    const BvhNode r = round_outward(n, bits);
    const Bounds3f rb = round_outward(b, bits);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 2; ++c) {
        CHECK(r.box[a][0][c] <= n.box[a][0][c]);
        CHECK(r.box[a][1][c] >= n.box[a][1][c]);
        CHECK(r.box[a][0][c] == rb.lo[a]);
        CHECK(r.box[a][1][c] == rb.hi[a]);
      }
    CHECK(r.ref[0] == n.ref[0]);
  }
  // Three fraction bits: -1.3 down to -1.375, 2.7 down to 2.5, 3.1 up to 3.25.
  const Bounds3f r3 = round_outward(b, 3);
  CHECK(r3.lo.x == -1.375f);
  CHECK(r3.lo.z == 2.5f);
  CHECK(r3.hi.z == 3.25f);
}
