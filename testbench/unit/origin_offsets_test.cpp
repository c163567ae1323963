// Emission-time origin offsets on hand-computed values.
#include <catch2/catch.hpp>

#include <cmath>

#include "datapath/origin_offsets.h"

using namespace vbsim;

TEST_CASE("Listing 6-1: integer-ulp offset away from zero, float offset near zero", "[offsets]") {
  const AdaptiveOffsetParams params;  // the chapter's constants
  // n = +z, ray leaving toward +z. x (1.0) is not offset (n.x = 0); y (0.01 < 1/32)
  // takes the float path with n.y = 0; z = -2 moves 256 ulps toward +z: -2 + 256 * 2^-23.
  const Vec3f p = offset_adaptive({1.0f, 0.01f, -2.0f}, {0, 0, 3}, {0, 0, 1}, params);
  CHECK(p.x == 1.0f);
  CHECK(p.y == 0.01f);
  CHECK(p.z == -2.0f + 256.0f * std::ldexp(1.0f, -23));
  // Near zero: y = 0.01 with n = +y moves by float_scale = 2^-16.
  const Vec3f q = offset_adaptive({1.0f, 0.01f, -2.0f}, {0, 1, 0}, {0, 1, 0}, params);
  CHECK(q.y == 0.01f + std::ldexp(1.0f, -16));
  // The normal is flipped onto the side the ray leaves into.
  const Vec3f r = offset_adaptive({1.0f, 0.01f, 4.0f}, {0, 0, 1}, {0, 0, -1}, params);
  CHECK(r.z == 4.0f - 256.0f * std::ldexp(1.0f, -22));  // 256 ulps of the binade below 4
}

TEST_CASE("fixed offsets move by eps along the unit normal or direction", "[offsets]") {
  const Vec3f p = offset_along_normal({0, 0, 0}, {0, 0, 10}, {1, 0, -1}, 0.5f);
  CHECK(p == Vec3f{0, 0, -0.5f});
  const Vec3f q = offset_along_direction({1, 1, 1}, {0, 3, 4}, 0.5f);
  CHECK(q.y == Approx(1.3f));
  CHECK(q.z == Approx(1.4f));
}

TEST_CASE("error-bound offset: pbrt's gamma(7) bound, then one float outward", "[offsets]") {
  const Triangle tri{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};  // plane z = 1, Ng = +z
  const BoundedPoint bp = barycentric_point_with_error(tri, 0.25f, 0.25f);
  CHECK(bp.p == Vec3f{0.25f, 0.25f, 1.0f});
  const float u = std::ldexp(1.0f, -24);
  const float gamma7 = 7 * u / (1 - 7 * u);
  CHECK(bp.error.z == Approx(gamma7 * 1.0f).epsilon(1e-6));
  const Vec3f up = offset_error_bound(bp, geometric_normal(tri), {0, 0, 1});
  CHECK(up.x == 0.25f);
  CHECK(up.y == 0.25f);
  CHECK(up.z > 1.0f + bp.error.z);  // beyond the whole error band
  CHECK(up.z == std::nextafter(1.0f + bp.error.z, 2.0f));
  const Vec3f down = offset_error_bound(bp, geometric_normal(tri), {0, 0, -1});
  CHECK(down.z < 1.0f - bp.error.z);
}
