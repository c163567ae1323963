// Bounds3f::extend's written-out fmin and fmax against the C library's fminf
// and fmaxf (called through pointers, so that the compiler cannot fold or
// reorder them) on signed zeros, infinities, NaNs, denormals and random
// values: a box's bits are what the library gives.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "scene/scene.h"

using namespace vbsim;

namespace {
bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }
float (*volatile library_fmin)(float, float) = ::fminf;
float (*volatile library_fmax)(float, float) = ::fmaxf;
}  // namespace

TEST_CASE("box bounds: fmin and fmax as the C library computes them", "[scene]") {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = INFINITY;
  std::vector<float> values = {0.0f, -0.0f, 1.0f, -1.0f, inf, -inf, nan, -nan, 1e-45f, -1e-45f, 0x1p126f, 3.5f};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  for (int i = 0; i < 200; ++i) values.push_back(u(rng));
  for (float a : values)
    for (float b : values) {
      INFO(a << " " << b);
      CHECK(same_bits(fmin_inline(a, b), library_fmin(a, b)));
      CHECK(same_bits(fmax_inline(a, b), library_fmax(a, b)));
    }
  Bounds3f box;
  box.extend({0.0f, -0.0f, 2.0f});
  box.extend({-0.0f, 0.0f, nan});
  CHECK(same_bits(box.lo.x, -0.0f));  // the later of equal values
  CHECK(same_bits(box.hi.y, 0.0f));
  CHECK(box.lo.z == 2.0f);  // a NaN coordinate does not enter
  CHECK(box.hi.z == 2.0f);
}
