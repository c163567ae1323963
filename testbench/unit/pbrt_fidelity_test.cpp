// offset-errbound and the pbrt-watertight tester against pbrt-v4's own
// arithmetic. Expected values come from float_emulation.h: pbrt-v4's
// operations transcribed in its order onto exact rational roundings, so a
// reordered sum, a missing FMA or a reciprocal where pbrt divides shows up as
// a differing bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "datapath/origin_offsets.h"
#include "datapath/pbrt_float.h"
#include "datapath/pbrt_interaction.h"
#include "datapath/testers.h"
#include "exact/exact_geometry.h"
#include "exact/rational_rounding.h"
#include "float_emulation.h"
#include "gen/pbrt_reintersect.h"

namespace vbsim {
namespace {

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(Vec3f a, Vec3f b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z); }

/// pbrt's pExp law: 10^U[-8, 8], positive.
struct PExp {
  std::mt19937 rng{12};
  float operator()() {
    return static_cast<float>(std::pow(10.0, std::uniform_real_distribution<double>(-8, 8)(rng)));
  }
  float unit() { return std::uniform_real_distribution<float>(0, 1)(rng); }
};

/// pbrt-v4's spawn origin (InteractionFromIntersection, Point3fi, OffsetRayOrigin),
/// on the emulated arithmetic.
Vec3f emulated_pbrt_origin(const Triangle& tri, float b0, float b1, float b2, Vec3f w) {
  const Vec3f ps[3] = {tri.v0, tri.v1, tri.v2};
  const float bs[3] = {b0, b1, b2};
  const float u = std::ldexp(1.0f, -24);
  const float g7 = emu::div(emu::mul(7, u), emu::sub(1, emu::mul(7, u)));
  Vec3f mid, err;
  for (int i = 0; i < 3; ++i) {
    float p = 0, abs_sum = 0;
    for (int k = 0; k < 3; ++k) {
      const float term = emu::mul(bs[k], ps[k][i]);
      p = k == 0 ? term : emu::add(p, term);
      abs_sum = k == 0 ? std::fabs(term) : emu::add(abs_sum, std::fabs(term));
    }
    const float e = emu::mul(g7, abs_sum);
    const float lo = e == 0 ? p : std::nextafter(emu::sub(p, e), -INFINITY);
    const float hi = e == 0 ? p : std::nextafter(emu::add(p, e), INFINITY);
    mid[i] = emu::div(emu::add(lo, hi), 2);
    err[i] = emu::div(emu::sub(hi, lo), 2);
  }
  const Vec3f n = emu::normalize(emu::cross(emu::sub(tri.v0, tri.v2), emu::sub(tri.v1, tri.v2)));
  const float dist = emu::dot({std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)}, err);
  Vec3f offset{emu::mul(dist, n.x), emu::mul(dist, n.y), emu::mul(dist, n.z)};
  if (emu::dot(w, n) < 0) offset = -offset;
  Vec3f po;
  for (int i = 0; i < 3; ++i) {
    po[i] = emu::add(mid[i], offset[i]);
    if (offset[i] > 0) po[i] = std::nextafter(po[i], INFINITY);
    if (offset[i] < 0) po[i] = std::nextafter(po[i], -INFINITY);
  }
  return po;
}

/// Signed distance of `p` from the plane of `tri` along its unit normal
/// (computed exactly, rounded to double at the end).
double signed_plane_distance(Vec3f p, const Triangle& tri) {
  const ExactVec3 v0 = to_exact(tri.v0), v1 = to_exact(tri.v1), v2 = to_exact(tri.v2), q = to_exact(p);
  const mpq_class e1x = v1.x - v0.x, e1y = v1.y - v0.y, e1z = v1.z - v0.z;
  const mpq_class e2x = v2.x - v0.x, e2y = v2.y - v0.y, e2z = v2.z - v0.z;
  const mpq_class nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
  const mpq_class s = (q.x - v0.x) * nx + (q.y - v0.y) * ny + (q.z - v0.z) * nz;
  const mpq_class n2 = nx * nx + ny * ny + nz * nz;
  return s.get_d() / std::sqrt(n2.get_d());
}

bool exact_hits(Vec3f o, Vec3f d, const Triangle& tri) {
  ExactRay r;
  r.o = to_exact(o);
  r.d = to_exact(d);
  return exact_intersect(r, tri).hit;
}

TEST_CASE("pbrt-v4 DifferenceOfProducts keeps what a plain float difference loses", "[pbrt]") {
  // a b = 1 + 2^-22 + 2^-46 and c d = 1 + 2^-22: the plain product rounds the
  // 2^-46 away, pbrt's two FMAs keep it.
  const float a = 1 + std::ldexp(1.0f, -23), c = 1, d = 1 + std::ldexp(1.0f, -22);
  CHECK(a * a - c * d == 0.0f);
  CHECK(pbrt::difference_of_products(a, a, c, d) == std::ldexp(1.0f, -46));
  CHECK(pbrt::sum_of_products(a, a, -c, d) == std::ldexp(1.0f, -46));
}

TEST_CASE("pbrt-v4 Cross, Dot and Normalize round as the reference does", "[pbrt]") {
  PExp value;
  std::mt19937 signs(3);
  const auto v = [&] {
    Vec3f r{value(), value(), value()};
    for (int i = 0; i < 3; ++i)
      if (signs() & 1u) r[i] = -r[i];
    return r;
  };
  for (int i = 0; i < 3000; ++i) {
    const Vec3f a = v(), b = v();
    INFO("case " << i);
    REQUIRE(same_bits(pbrt::pbrt_cross(a, b), emu::cross(a, b)));
    REQUIRE(same_bits(pbrt::pbrt_dot(a, b), emu::dot(a, b)));
    const Vec3f n = pbrt::pbrt_cross(a, b);
    if (is_finite(n) && pbrt::pbrt_length_squared(n) > 0 && std::isfinite(pbrt::pbrt_length_squared(n)))
      REQUIRE(same_bits(pbrt::pbrt_normalize(n), emu::normalize(n)));
  }
}

// The needle triangle of issue 12: a float cross product of v1 - v0 and v2 - v0
// cancels its x component to 0, pbrt's FMA cross of p0 - p2 and p1 - p2 keeps
// it, and a shadow ray that grazes the plane sees the two normals on opposite sides.
TEST_CASE("pbrt-v4's normal of a needle triangle puts the shadow ray's origin above the plane", "[pbrt]") {
  const Triangle tri{{-984.069641f, 35810.5781f, -1112278.62f}, {7.77e-6f, 5.08e-6f, 1.95e-5f},
                     {-0.539237f, -1.4997e-4f, 2.03e-6f}};
  const float b1 = 0.23646055f, b2 = 0.13827293f, b0 = 1.0f - b1 - b2;
  const Vec3f d{615.3802f, -22391.154f, 695469.1f};

  const Vec3f plain_n = normalize(geometric_normal(tri));
  CHECK(plain_n.x == 0.0f);  // cancelled
  CHECK(dot(d, plain_n) == Approx(-0.842).margin(0.001));
  const Vec3f pbrt_n = pbrt::pbrt_normalize(pbrt::pbrt_cross(tri.v0 - tri.v2, tri.v1 - tri.v2));
  CHECK(same_bits(pbrt_n, emu::normalize(emu::cross(emu::sub(tri.v0, tri.v2), emu::sub(tri.v1, tri.v2)))));
  CHECK(pbrt_n.x == Approx(2.8842535e-4).epsilon(1e-6));  // the exact unit normal's 2.88425350e-4
  CHECK(pbrt::pbrt_dot(d, pbrt_n) == Approx(0.0466).margin(0.0001));

  OffsetOutcome outcome = OffsetOutcome::Reference;
  const Vec3f o = offset_error_bound({}, tri, b0, b1, b2, nullptr, d, outcome);
  CHECK(outcome == OffsetOutcome::Reference);
  CHECK(same_bits(o, emulated_pbrt_origin(tri, b0, b1, b2, d)));
  CHECK(signed_plane_distance(o, tri) == Approx(0.0279).margin(0.0005));  // above, on d's side
  CHECK_FALSE(exact_hits(o, d, tri));
  Ray ray;
  ray.o = o;
  ray.d = d;
  Hit hit;
  CHECK_FALSE(PbrtWatertightTester(ray).intersect(tri, INFINITY, hit));

  // The offset as vbsim computed it before (the unwidened bound gamma(7) sum
  // |b_i p_i| on the plain point, along the plain float normal, one float
  // outward): the origin ends up 0.023 below the plane, where the ray meets
  // the triangle again.
  const Vec3f p = b0 * tri.v0 + b1 * tri.v1 + b2 * tri.v2;
  const Vec3f err = pbrt::gamma(7) * (abs(b0 * tri.v0) + abs(b1 * tri.v1) + abs(b2 * tri.v2));
  Vec3f offset = dot(abs(plain_n), err) * plain_n;
  if (dot(d, plain_n) < 0) offset = -offset;
  Vec3f below = p + offset;
  for (int i = 0; i < 3; ++i)
    if (offset[i] != 0) below[i] = std::nextafter(below[i], offset[i] > 0 ? INFINITY : -INFINITY);
  CHECK(signed_plane_distance(below, tri) == Approx(-0.023).margin(0.0005));
  CHECK(exact_hits(below, d, tri));
  ray.o = below;
  REQUIRE(ThreeHalfPlaneTester(ray).intersect(tri, INFINITY, hit));
  CHECK(hit.t == Approx(0.518).margin(0.001));  // the float tester's re-hit of issue 12
}

TEST_CASE("pbrt-v4 spawn origins match the reference bit for bit on random triangles", "[pbrt]") {
  PExp value;
  int checked = 0;
  while (checked < 2000) {
    const Triangle tri{{value(), value(), value()}, {value(), value(), value()}, {value(), value(), value()}};
    const Vec3f n = pbrt::pbrt_cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
    if (!(pbrt::pbrt_length_squared(n) >= 1e-20) || !std::isfinite(pbrt::pbrt_length_squared(n))) continue;
    float b1 = value.unit(), b2 = value.unit();
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const float b0 = 1 - b1 - b2;
    const Vec3f w{value.unit() - 0.5f, value.unit() - 0.5f, value.unit() - 0.5f};
    OffsetOutcome outcome = OffsetOutcome::Reference;
    const Vec3f o = offset_error_bound({}, tri, b0, b1, b2, nullptr, w, outcome);
    INFO("case " << checked);
    REQUIRE(outcome == OffsetOutcome::Reference);
    REQUIRE(same_bits(o, emulated_pbrt_origin(tri, b0, b1, b2, w)));
    ++checked;
  }
}

/// pbrt's double-precision redo of an edge function, a b - c d: exact products,
/// the difference rounded to double, then to float.
float emulated_double_edge(float a, float b, float c, float d) {
  return static_cast<float>(round_to_nearest_double(emu::exact(a) * emu::exact(b) - emu::exact(c) * emu::exact(d)));
}

/// pbrt-v4's IntersectTriangle on the emulated arithmetic, up to its
/// conservative t check.
bool emulated_intersect(Vec3f o, Vec3f d, const Triangle& tri, float tmax, PbrtTriangleHit& out) {
  const Vec3f q[3] = {emu::sub(tri.v0, o), emu::sub(tri.v1, o), emu::sub(tri.v2, o)};
  const Vec3f ad = abs(d);
  const int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  const int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  const float sx = emu::div(-d[kx], d[kz]), sy = emu::div(-d[ky], d[kz]), sz = emu::div(1, d[kz]);
  float x[3], y[3], z[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = emu::add(q[i][kx], emu::mul(sx, q[i][kz]));
    y[i] = emu::add(q[i][ky], emu::mul(sy, q[i][kz]));
    z[i] = q[i][kz];
  }
  float e0 = emu::dop(x[1], y[2], y[1], x[2]);
  float e1 = emu::dop(x[2], y[0], y[2], x[0]);
  float e2 = emu::dop(x[0], y[1], y[0], x[1]);
  if (e0 == 0 || e1 == 0 || e2 == 0) {
    e0 = emulated_double_edge(y[2], x[1], x[2], y[1]);
    e1 = emulated_double_edge(y[0], x[2], x[0], y[2]);
    e2 = emulated_double_edge(y[1], x[0], x[1], y[0]);
  }
  if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return false;
  const float det = emu::add(emu::add(e0, e1), e2);
  if (det == 0) return false;
  for (float& zi : z) zi = emu::mul(zi, sz);
  const float ts = emu::add(emu::add(emu::mul(e0, z[0]), emu::mul(e1, z[1])), emu::mul(e2, z[2]));
  const bool bounded = std::isfinite(tmax);  // tmax * det is +-inf otherwise, never passed
  if (det < 0 && (ts >= 0 || (bounded && ts < emu::mul(tmax, det)))) return false;
  if (det > 0 && (ts <= 0 || (bounded && ts > emu::mul(tmax, det)))) return false;
  const float inv = emu::div(1, det);
  out = {emu::mul(e0, inv), emu::mul(e1, inv), emu::mul(e2, inv), emu::mul(ts, inv), false};
  return true;  // before pbrt's conservative t check
}

TEST_CASE("pbrt-watertight is pbrt-v4's IntersectTriangle bit for bit", "[pbrt][tester]") {
  PExp value;
  int hits = 0, cases = 0;
  while (cases < 3000) {
    const Triangle tri{{value(), value(), value()}, {value(), value(), value()}, {value(), value(), value()}};
    float b1 = value.unit(), b2 = value.unit();
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const Vec3f target = (1 - b1 - b2) * tri.v0 + b1 * tri.v1 + b2 * tri.v2;
    Ray ray;
    ray.o = {value(), value(), value()};
    ray.d = target - ray.o;
    PbrtTriangleHit want{}, got{};
    const Vec3f n = pbrt::pbrt_cross(tri.v2 - tri.v0, tri.v1 - tri.v0);
    if (pbrt::pbrt_length_squared(n) == 0) continue;
    ++cases;
    const bool emulated = emulated_intersect(ray.o, ray.d, tri, INFINITY, want);
    const bool ours = PbrtWatertightTester(ray).intersect_triangle(tri, INFINITY, got);
    INFO("case " << cases);
    if (!emulated) {
      REQUIRE_FALSE(ours);
      continue;
    }
    if (!ours) continue;  // dropped by the conservative t check
    ++hits;
    REQUIRE(same_bits(got.b0, want.b0));
    REQUIRE(same_bits(got.b1, want.b1));
    REQUIRE(same_bits(got.b2, want.b2));
    REQUIRE(same_bits(got.t, want.t));
    // front: dot(d, Ng) < 0 with Ng = (v1 - v0) x (v2 - v0), decided exactly.
    const ExactVec3 v0 = to_exact(tri.v0), v1 = to_exact(tri.v1), v2 = to_exact(tri.v2), dd = to_exact(ray.d);
    const mpq_class ax = v1.x - v0.x, ay = v1.y - v0.y, az = v1.z - v0.z;
    const mpq_class bx = v2.x - v0.x, by = v2.y - v0.y, bz = v2.z - v0.z;
    const mpq_class side = dd.x * (ay * bz - az * by) + dd.y * (az * bx - ax * bz) + dd.z * (ax * by - ay * bx);
    REQUIRE(got.front == (side < 0));
  }
  CHECK(hits > 2500);
}

// pbrt-v4's own "Triangle, BadCases": a ray pbrt must not report as a hit.
TEST_CASE("pbrt-watertight passes pbrt-v4's BadCases ray", "[pbrt][tester]") {
  const Triangle tri{{-1113.45459f, -79.049614f, -56.2431908f},
                     {-1113.45459f, -87.0922699f, -56.2431908f},
                     {-1113.45459f, -79.2090149f, -56.2431908f}};
  Ray ray;
  ray.o = {-1081.47925f, 99.9999542f, 87.7701111f};
  ray.d = {-32.1072998f, -183.355865f, -144.607635f};
  PbrtTriangleHit h;
  CHECK_FALSE(PbrtWatertightTester(ray).intersect_triangle(tri, 0.9999f, h));
  Hit hit;
  CHECK_FALSE(PbrtWatertightTester(ray).intersect(tri, 0.9999f, hit));
}

TEST_CASE("pbrt-v4 face-forwards the normal to the vertex normals", "[pbrt]") {
  const Triangle tri{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};  // Ng = +z; pbrt's Cross(p0 - p2, p1 - p2) too
  const std::array<Vec3f, 3> down{{{0, 0, -1}, {0, 0, -1}, {0, 0, -1}}};
  const pbrt::SurfacePoint plain = pbrt::triangle_interaction(tri, 0.5f, 0.25f, 0.25f, nullptr);
  const pbrt::SurfacePoint flipped = pbrt::triangle_interaction(tri, 0.5f, 0.25f, 0.25f, &down);
  CHECK(plain.n == Vec3f{0, 0, 1});
  CHECK(flipped.n == Vec3f{0, 0, -1});
  // The side of the offset comes from w, so only a w in the plane tells them apart:
  // OffsetRayOrigin keeps +offset when dot(w, n) is exactly 0.
  const Vec3f w{1, 0, 0};
  CHECK(pbrt::offset_ray_origin(plain.pi, plain.n, w).z > 1.0f);
  CHECK(pbrt::offset_ray_origin(flipped.pi, flipped.n, w).z < 1.0f);
  CHECK(pbrt::offset_ray_origin(plain.pi, plain.n, {0, 0, -1}) ==
        pbrt::offset_ray_origin(flipped.pi, flipped.n, {0, 0, -1}));
}

TEST_CASE("pbrt-v4's interval point is the midpoint of the widened bounds", "[pbrt]") {
  // p = 1, e = 2^-20: [next_down(1 - e), next_up(1 + e)] = [1 - e - 2^-24, 1 + e + 2^-23];
  // lo + hi = 2 + 2^-24 rounds to 2 (the ulp is 2^-22 there), so the point is 1,
  // and the error is the half width e + 3 * 2^-25, wider than e.
  const float e = std::ldexp(1.0f, -20);
  const pbrt::PointInterval pi = pbrt::PointInterval::from_value_and_error({1, 1, 1}, {e, 0, e});
  CHECK(pi.lo.x == 1 - e - std::ldexp(1.0f, -24));
  CHECK(pi.hi.x == 1 + e + std::ldexp(1.0f, -23));
  CHECK(pi.point().x == 1.0f);
  CHECK(pi.error().x == e + 3 * std::ldexp(1.0f, -25));
  CHECK(pi.lo.y == 1.0f);  // no error: the exact point
  CHECK(pi.error().y == 0.0f);
}

// pbrt-v4's RNG is PCG32: with seed 42 and sequence 54 it gives the PCG32
// reference implementation's published first outputs (pcg32-demo, round 1).
TEST_CASE("pbrt-v4's RNG is the reference PCG32", "[pbrt]") {
  PbrtRng rng(54, 42);
  const uint32_t published[] = {0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293, 0xbfa4784b, 0xcbed606e};
  for (uint32_t want : published) CHECK(rng.next_u32() == want);
  // Its float draw: u32 * 2^-32 in float, capped below 1.
  PbrtRng a(7), b(7);
  for (int i = 0; i < 100; ++i) {
    const float f = a.uniform_float();
    CHECK(f == std::min(0x1.fffffep-1f, static_cast<float>(b.next_u32()) * 0x1p-32f));
    CHECK((f >= 0.0f && f < 1.0f));
  }
}

}  // namespace
}  // namespace vbsim
