// Emission-time origin offsets on hand-computed values, and the defined outcome
// of degenerate normals (zero-area, underflowing and overflowing triangles).
#include <catch2/catch.hpp>

#include <cfloat>
#include <cmath>

#include "datapath/float_bits.h"
#include "datapath/origin_offsets.h"
#include "datapath/pbrt_float.h"
#include "exact/exact_geometry.h"

using namespace vbsim;

namespace {

Vec3f unit_diagonal() {
  const float c = static_cast<float>(1.0 / std::sqrt(3.0));
  return {c, c, c};
}

/// (s, 0, 0), (0, s, 0), (0, 0, s): plane x + y + z = s, unit normal (1,1,1)/sqrt(3).
Triangle diagonal_triangle(float s) { return {{s, 0, 0}, {0, s, 0}, {0, 0, s}}; }

}  // namespace

TEST_CASE("Listing 6-1: integer-ulp offset away from zero, float offset near zero", "[offsets]") {
  const AdaptiveOffsetParams params;  // the chapter's constants
  // n = +z: x (1.0) is not moved (n.x = 0); y (0.01 < 1/32) takes the float path
  // with n.y = 0; z = -2 moves int(256 * 1) = 256 ulps toward +z, i.e. its bit
  // pattern loses 256: -2 + 256 * 2^-23 (the binade below 2).
  const Vec3f p = offset_ray_listing_6_1({1.0f, 0.01f, -2.0f}, {0, 0, 1}, params);
  CHECK(p.x == 1.0f);
  CHECK(p.y == 0.01f);
  CHECK(p.z == -2.0f + 256.0f * std::ldexp(1.0f, -23));
  // Near zero: y = 0.01 with n = +y moves by float_scale = 2^-16.
  const Vec3f q = offset_ray_listing_6_1({1.0f, 0.01f, -2.0f}, {0, 1, 0}, params);
  CHECK(q.y == 0.01f + std::ldexp(1.0f, -16));
  // int(256 * 0.6) = 153: truncation, as the chapter's int3 conversion.
  const Vec3f r = offset_ray_listing_6_1({4.0f, 0, 0}, {0.6f, 0, 0.8f}, params);
  CHECK(float_bits(r.x) == float_bits(4.0f) + 153);
}

TEST_CASE("offset-adaptive flips the unit geometric normal onto the ray's side", "[offsets]") {
  const Triangle tri{{0, 0, 4}, {2, 0, 4}, {0, 2, 4}};  // Ng = (0, 0, 4)
  OffsetOutcome outcome = OffsetOutcome::Reference;
  const Vec3f down = offset_adaptive({1.0f, 0.01f, 4.0f}, tri, {0, 0, -1}, AdaptiveOffsetParams{}, outcome);
  CHECK(outcome == OffsetOutcome::Reference);
  CHECK(down.z == 4.0f - 256.0f * std::ldexp(1.0f, -22));  // 256 ulps of the binade below 4
  const Vec3f up = offset_adaptive({1.0f, 0.01f, 4.0f}, tri, {0, 0, 1}, AdaptiveOffsetParams{}, outcome);
  CHECK(up.z == 4.0f + 256.0f * std::ldexp(1.0f, -21));
}

TEST_CASE("fixed offsets move by eps along the unit normal or direction", "[offsets]") {
  const Triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  OffsetOutcome outcome = OffsetOutcome::Reference;
  const Vec3f p = offset_along_normal({0, 0, 0}, {0, 0, 10}, tri, {1, 0, -1}, 0.5f, outcome);
  CHECK(p == Vec3f{0, 0, -0.5f});
  CHECK(outcome == OffsetOutcome::Reference);
  const Vec3f q = offset_along_direction({1, 1, 1}, {0, 3, 4}, 0.5f);
  CHECK(q.y == Approx(1.3f));
  CHECK(q.z == Approx(1.4f));
}

TEST_CASE("error-bound offset: pbrt's widened gamma(7) bound, then one float outward", "[offsets]") {
  const Triangle tri{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};  // plane z = 1, Ng = +z
  // p = (0.25, 0.25, 1): every product is exact. z's error is gamma(7) (0.5 + 0.25 + 0.25);
  // the interval [next_down(1 - e), next_up(1 + e)] has half width e' > e, the
  // offset is |n| . error = e' along +z, and the sum is moved one float up.
  const float e = pbrt::gamma(7);
  const float lo = pbrt::next_float_down(1 - e), hi = pbrt::next_float_up(1 + e);
  const float e_wide = (hi - lo) / 2, mid = (lo + hi) / 2;
  OffsetOutcome outcome = OffsetOutcome::Reference;
  const Vec3f up = offset_error_bound({}, tri, 0.5f, 0.25f, 0.25f, nullptr, {0, 0, 1}, outcome);
  CHECK(outcome == OffsetOutcome::Reference);
  CHECK(up.z == pbrt::next_float_up(mid + e_wide));
  CHECK(up.z > 1.0f + e);  // beyond the whole error band
  const Vec3f down = offset_error_bound({}, tri, 0.5f, 0.25f, 0.25f, nullptr, {0, 0, -1}, outcome);
  CHECK(down.z == pbrt::next_float_down(mid - e_wide));
  // x and y: errors gamma(7) * 0.25 around exact 0.25, the offset along z only.
  CHECK(up.x == (pbrt::next_float_down(0.25f - e * 0.25f) + pbrt::next_float_up(0.25f + e * 0.25f)) / 2);
}

// Degenerate normals: the float unit normal is NaN (0/0 or inf/inf). Before
// this outcome was defined, Listing 6-1 converted 256 * NaN to an int (undefined;
// INT_MIN on x86) and negated it for negative coordinates (undefined again).
TEST_CASE("a zero-area triangle with negative coordinates leaves the origin unchanged", "[offsets][degenerate]") {
  const Triangle tri{{-1, -2, -3}, {-2, -4, -6}, {-3, -6, -9}};  // collinear: Ng = 0 exactly
  REQUIRE(geometric_normal(tri) == Vec3f{0, 0, 0});
  Vec3f n;
  CHECK_FALSE(unit_normal_in_double(tri, n));
  const Vec3f p{-2, -4, -6};
  OffsetOutcome a = OffsetOutcome::Reference, b = a, c = a;
  CHECK(offset_adaptive(p, tri, {1, 0, 0}, AdaptiveOffsetParams{}, a) == p);
  CHECK(offset_along_normal(p, geometric_normal(tri), tri, {1, 0, 0}, 1e-4f, b) == p);
  CHECK(offset_error_bound(p, tri, 0.5f, 0.25f, 0.25f, nullptr, {1, 0, 0}, c) == p);
  CHECK(a == OffsetOutcome::NotOffset);
  CHECK(b == OffsetOutcome::NotOffset);
  CHECK(c == OffsetOutcome::NotOffset);
}

TEST_CASE("1e-30 and denormal triangles take the double-precision normal", "[offsets][degenerate]") {
  for (float s : {1e-30f, 1e-44f}) {
    INFO("size " << s);
    const Triangle tri = diagonal_triangle(s);
    REQUIRE(geometric_normal(tri) == Vec3f{0, 0, 0});  // the products underflow
    Vec3f n;
    REQUIRE(unit_normal_in_double(tri, n));
    CHECK(n == unit_diagonal());
    const Vec3f p{s / 4, s / 4, s / 2};
    // Listing 6-1's float path (|p| < 1/32): p + 2^-16 n.
    OffsetOutcome outcome = OffsetOutcome::Reference;
    const Vec3f o = offset_adaptive(p, tri, {1, 1, 1}, AdaptiveOffsetParams{}, outcome);
    CHECK(outcome == OffsetOutcome::NormalInDouble);
    CHECK(o == p + std::ldexp(1.0f, -16) * unit_diagonal());
    // pbrt's point and bound are finite. At 1e-30 the offset moves the origin
    // below the plane for d = -n; at denormal sizes gamma(7) |b p| underflows to
    // 0, so pbrt's own arithmetic offsets by nothing.
    outcome = OffsetOutcome::Reference;
    const Vec3f e = offset_error_bound(p, tri, 0.25f, 0.25f, 0.5f, nullptr, {-1, -1, -1}, outcome);
    CHECK(outcome == OffsetOutcome::NormalInDouble);
    CHECK(is_finite(e));
    if (s > 1e-38f) CHECK(e.x + e.y + e.z < s);
  }
}

TEST_CASE("a 3e38 triangle's overflowing normal is taken in double precision", "[offsets][degenerate]") {
  const Triangle tri = diagonal_triangle(3e38f);
  REQUIRE_FALSE(is_finite(normalize(geometric_normal(tri))));
  const Vec3f p{1e38f, 1e38f, 1e38f};
  OffsetOutcome outcome = OffsetOutcome::Reference;
  const Vec3f o = offset_adaptive(p, tri, {1, 1, 1}, AdaptiveOffsetParams{}, outcome);
  CHECK(outcome == OffsetOutcome::NormalInDouble);
  const int32_t ulps = static_cast<int32_t>(256.0f * unit_diagonal().x);  // int(147.8) = 147
  CHECK(o.x == bits_float(float_bits(1e38f) + ulps));
  outcome = OffsetOutcome::Reference;
  const float third = 1.0f / 3;
  const Vec3f e = offset_error_bound(p, tri, third, third, 1 - third - third, nullptr, {1, 1, 1}, outcome);
  CHECK(outcome == OffsetOutcome::NormalInDouble);
  CHECK(is_finite(e));
  CHECK(e.x > p.x);
}

TEST_CASE("an error bound that overflows leaves the origin as given", "[offsets][degenerate]") {
  // The plane x = FLT_MAX: the normal is fine, but p.x + error overflows, so
  // pbrt's interval has an infinite end and its midpoint is not finite.
  const Triangle tri{{FLT_MAX, 0, 0}, {FLT_MAX, 1, 0}, {FLT_MAX, 0, 1}};
  const Vec3f given{FLT_MAX, 0.25f, 0.25f};
  OffsetOutcome outcome = OffsetOutcome::Reference;
  CHECK(offset_error_bound(given, tri, 0.5f, 0.25f, 0.25f, nullptr, {-1, 0, 0}, outcome) == given);
  CHECK(outcome == OffsetOutcome::NotOffset);
}

TEST_CASE("Listing 6-1 saturates an int_scale beyond the int range", "[offsets][degenerate]") {
  AdaptiveOffsetParams params;
  params.int_scale = 1e12f;  // int(1e12) does not exist
  const Vec3f o = offset_ray_listing_6_1({-8.0f, 1.0f, 1.0f}, {1, 0, 0}, params);
  // The bits of -8 step by -(INT_MAX) and wrap, as 32-bit integers do: a defined value.
  CHECK(float_bits(o.x) == float_bits(-8.0f) - 2147483647u);
}
