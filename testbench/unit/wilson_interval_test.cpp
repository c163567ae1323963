// Wilson score interval against published 95% values and the closed form of
// the zero-count upper bound.
#include <catch2/catch.hpp>

#include "score/wilson_interval.h"

using vbsim::wilson_interval;

TEST_CASE("Wilson interval matches published 95 percent values", "[score][wilson]") {
  // Textbook values (e.g. Newcombe 1998, Table I; Brown, Cai and DasGupta 2001).
  const auto half = wilson_interval(5, 10);
  CHECK(half.estimate == 0.5);
  CHECK(half.lower == Approx(0.2366).margin(5e-5));
  CHECK(half.upper == Approx(0.7634).margin(5e-5));
  const auto one = wilson_interval(1, 100);
  CHECK(one.lower == Approx(0.0018).margin(5e-5));
  CHECK(one.upper == Approx(0.0545).margin(5e-5));
  const auto many = wilson_interval(81, 263);  // Newcombe's example 81/263
  CHECK(many.lower == Approx(0.2553).margin(5e-5));
  CHECK(many.upper == Approx(0.3662).margin(5e-5));
}

TEST_CASE("Wilson interval of a zero count has a non-zero upper bound", "[score][wilson]") {
  // k = 0: centre = half-width = (z^2 / 2) / (n + z^2), so upper = z^2 / (n + z^2).
  const double z2 = 1.959963984540054 * 1.959963984540054;  // 3.841459
  const auto ten = wilson_interval(0, 10);
  CHECK(ten.estimate == 0.0);
  CHECK(ten.lower == 0.0);
  CHECK(ten.upper == Approx(0.2775).margin(5e-5));
  CHECK(ten.upper == Approx(z2 / (10 + z2)).epsilon(1e-12));
  const auto million = wilson_interval(0, 1000000);
  CHECK(million.upper == Approx(3.8414e-6).epsilon(1e-4));  // "rule of 3.84"
  // All successes mirror the zero count.
  const auto all = wilson_interval(10, 10);
  CHECK(all.upper == 1.0);
  CHECK(all.lower == Approx(1 - ten.upper).epsilon(1e-12));
}

TEST_CASE("Wilson interval with no trials says nothing is known", "[score][wilson]") {
  const auto none = wilson_interval(0, 0);
  CHECK(none.lower == 0.0);
  CHECK(none.upper == 1.0);
}
