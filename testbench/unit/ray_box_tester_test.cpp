// RayBoxTester (the slab test of the closest-hit search): hand-computed cases,
// its two-child forms against each other, and its robustness against an exact
// rational slab test (it never culls a box the exact test says the ray meets).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include <gmpxx.h>

#include "datapath/ray_box_tester.h"

using namespace vbsim;

namespace {

Ray make_ray(Vec3f o, Vec3f d, float tmin = 0.0f, float tmax = INFINITY) {
  Ray r;
  r.o = o;
  r.d = d;
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

Bounds3f box(Vec3f lo, Vec3f hi) {
  Bounds3f b;
  b.lo = lo;
  b.hi = hi;
  return b;
}

BvhNode node(const Bounds3f& child0, const Bounds3f& child1) {
  BvhNode n{};
  n.set_child(0, child0, BvhRef{0, 1});
  n.set_child(1, child1, BvhRef{1, 1});
  return n;
}

// Exact slab test in rationals over the closed box and [tmin, tmax], for the
// direction the tester uses: components below 1e-18 in magnitude replaced by
// +-1e-18 (so a ray running exactly in a face plane may be culled; that is the
// documented substitution, not rounding).
bool exact_meets(const Ray& r, const Bounds3f& b) {
  mpq_class tn(r.tmin), tf;
  bool bounded = std::isfinite(r.tmax);
  if (bounded) tf = r.tmax;
  for (int a = 0; a < 3; ++a) {
    const float da = std::fabs(r.d[a]) < 1e-18f ? std::copysign(1e-18f, r.d[a]) : r.d[a];
    const mpq_class o(r.o[a]), lo(b.lo[a]), hi(b.hi[a]), d(da);
    mpq_class near = (lo - o) / d, far = (hi - o) / d;
    if (d < 0) std::swap(near, far);
    if (near > tn) tn = near;
    if (!bounded || far < tf) tf = far, bounded = true;
  }
  return tn <= tf;
}

}  // namespace

TEST_CASE("two-child slab test: hand-computed entries, misses and the ray interval", "[closest_hit]") {
  const Bounds3f ahead = box({1, -1, -1}, {2, 1, 1}), behind = box({-3, -1, -1}, {-2, 1, 1});
  const BvhNode n = node(ahead, behind);
  float t0 = -1, t1 = -1;
  SECTION("+x meets child 0 at t = 1, child 1 is behind the origin") {
    CHECK(RayBoxTester(make_ray({0, 0, 0}, {1, 0, 0})).hits(n, INFINITY, t0, t1) == 1u);
    CHECK(t0 == 1.0f);
  }
  SECTION("-x with |d| = 2 meets child 1 at t = 1") {
    CHECK(RayBoxTester(make_ray({0, 0, 0}, {-2, 0, 0})).hits(n, INFINITY, t0, t1) == 2u);
    CHECK(t1 == 1.0f);
  }
  SECTION("tmax before the box, tmin past it") {
    CHECK(RayBoxTester(make_ray({0, 0, 0}, {1, 0, 0})).hits(n, 0.5f, t0, t1) == 0u);
    CHECK(RayBoxTester(make_ray({0, 0, 0}, {1, 0, 0}, 2.5f)).hits(n, INFINITY, t0, t1) == 0u);
  }
  SECTION("an origin inside a box enters it at tmin") {
    CHECK(RayBoxTester(make_ray({1.5f, 0, 0}, {0, 1, 0}, 0.25f)).hits(n, INFINITY, t0, t1) == 1u);
    CHECK(t0 == 0.25f);
  }
  SECTION("zero direction components: the origin's slab decides") {
    const BvhNode side = node(box({1, 0.5f, -1}, {2, 1, 1}), box({1, -1, -1}, {2, 1, 1}));
    CHECK(RayBoxTester(make_ray({0, 0, 0}, {1, 0, 0})).hits(side, INFINITY, t0, t1) == 2u);
    CHECK(RayBoxTester(make_ray({0, 0, 0}, {1, -0.0f, 0})).hits(side, INFINITY, t0, t1) == 2u);
  }
  SECTION("a flat box the ray crosses, and one whose plane the ray runs in") {
    const BvhNode flat = node(box({1, -1, -1}, {1, 1, 1}), box({0, 0, 0}, {5, 0, 0}));
    CHECK(RayBoxTester(make_ray({0, 0, 0}, {1, 0, 0})).hits(flat, INFINITY, t0, t1) == 3u);
    CHECK(t0 == 1.0f);
    CHECK(t1 == 0.0f);
  }
  SECTION("the root form agrees") {
    const RayBoxTester tester(make_ray({0, 0, 0}, {1, 0, 0}));
    CHECK(tester.hits(ahead, INFINITY));
    CHECK_FALSE(tester.hits(behind, INFINITY));
    CHECK_FALSE(tester.hits(ahead, 0.5f));
  }
}

TEST_CASE("slab test never culls a box the exact test meets, its forms agree bit for bit", "[closest_hit]") {
  std::mt19937 rng(77);
  std::uniform_real_distribution<float> coord(-4, 4), unit(0, 1);
  std::uniform_int_distribution<int> pick(0, 5);
  int exact_hits = 0, grazing = 0;
  for (int i = 0; i < 4000; ++i) {
    Vec3f o{coord(rng), coord(rng), coord(rng)}, d{coord(rng), coord(rng), coord(rng)};
    if (pick(rng) == 0) d[pick(rng) % 3] = 0.0f;  // axis-parallel in one component
    if (i % 7 == 3) d[i % 3] = -0.0f;             // ... with a negative zero (its near side is the high bound)
    if (d == Vec3f{}) d = {1, 0, 0};
    const float tmax = pick(rng) < 2 ? 0.5f + unit(rng) : INFINITY;
    const Ray ray = make_ray(o, d, 0.0f, tmax);
    // Child 0: random; child 1: a box with a corner on a point of the ray
    // (rounded to float), so that the ray grazes it.
    Bounds3f b[2];
    for (Bounds3f& bb : b) {
      const Vec3f p{coord(rng), coord(rng), coord(rng)}, q{coord(rng), coord(rng), coord(rng)};
      bb = box({std::min(p.x, q.x), std::min(p.y, q.y), std::min(p.z, q.z)},
               {std::max(p.x, q.x), std::max(p.y, q.y), std::max(p.z, q.z)});
    }
    const Vec3f corner = o + (unit(rng) * 1.5f) * d;
    const Vec3f size{unit(rng), unit(rng), unit(rng)};
    const Vec3f away{d.x >= 0 ? 1.0f : -1.0f, d.y >= 0 ? -1.0f : 1.0f, pick(rng) < 3 ? 1.0f : -1.0f};
    const Vec3f far_corner{corner.x + away.x * size.x, corner.y + away.y * size.y, corner.z + away.z * size.z};
    b[1] = box({std::min(corner.x, far_corner.x), std::min(corner.y, far_corner.y), std::min(corner.z, far_corner.z)},
               {std::max(corner.x, far_corner.x), std::max(corner.y, far_corner.y), std::max(corner.z, far_corner.z)});
    const BvhNode n = node(b[0], b[1]);
    const RayBoxTester tester(ray);
    float e0 = 0, e1 = 0;
    const unsigned mask = tester.hits(n, tmax, e0, e1);
    for (int c = 0; c < 2; ++c) {
      const bool exact = exact_meets(ray, b[c]);
      exact_hits += exact;
      grazing += c == 1 && exact;
      INFO("case " << i << " child " << c);
      if (exact) CHECK((mask >> c & 1u) == 1u);
      CHECK(tester.hits(b[c], tmax) == ((mask >> c & 1u) == 1u));
    }
    float s0 = 0, s1 = 0;
    CHECK(tester.hits_scalar(n, tmax, s0, s1) == mask);
    if (mask & 1u) CHECK(s0 == e0);
    if (mask & 2u) CHECK(s1 == e1);
#if defined(__SSE2__)
    float v0 = 0, v1 = 0;
    CHECK(tester.hits_sse2(n, tmax, v0, v1) == mask);
    if (mask & 1u) CHECK(v0 == e0);
    if (mask & 2u) CHECK(v1 == e1);
#endif
  }
  CHECK(exact_hits > 1500);
  CHECK(grazing > 500);
}

TEST_CASE("the latched reciprocals are safe_reciprocal's, zeros and tiny components included", "[closest_hit]") {
  // Hand: 1 / 4 = 0.25; |d| < 1e-18 becomes 1e-18 of d's sign (so 1 / d = +-1e18,
  // rounded once); a zero keeps its sign; 1e-18 itself is not replaced.
  const float tiny = 1e-18f;
  const float components[] = {4.0f, -0.5f, 3.0f, 0.0f, -0.0f, 1e-19f, -1e-19f, tiny, -tiny, 1e-45f,
                              std::nextafter(tiny, 0.0f), 7e37f, -1e-10f};
  const float expected_tiny = 1.0f / tiny;
  for (float x : components)
    for (int axis = 0; axis < 3; ++axis) {
      Vec3f d{1.0f, 1.0f, 1.0f};
      d[axis] = x;
      const RayBoxTester box(make_ray({0, 0, 0}, d));
      INFO("component " << x << " on axis " << axis);
      const float got = box.reciprocal(axis), want = RayBoxTester::safe_reciprocal(x);
      CHECK(std::memcmp(&got, &want, sizeof got) == 0);
      CHECK(box.reciprocal((axis + 1) % 3) == 1.0f);
      if (x == 4.0f) CHECK(got == 0.25f);
      if (std::fabs(x) < tiny) CHECK(got == std::copysign(expected_tiny, x));
    }
}

#if defined(__SSE2__)
TEST_CASE("the one-box test in one SSE2 vector answers as the scalar one", "[closest_hit]") {
  // The wide searches test the root box this way. Directions with +0, -0, tiny,
  // huge and negative components; origins inside, outside, on a face and on a
  // corner; flat and point boxes; intervals empty, closed on a face and open.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coord(-4, 4);
  std::uniform_int_distribution<int> pick(0, 7);
  const float special[] = {0.0f, -0.0f, 1e-20f, -1e-20f, 1e-18f, 3e38f, -3e38f, 1.0f, -1.0f};
  int met = 0, missed = 0;
  for (int i = 0; i < 20000; ++i) {
    Vec3f lo{coord(rng), coord(rng), coord(rng)}, hi = lo;
    for (int a = 0; a < 3; ++a)
      if (pick(rng) != 0) hi[a] = lo[a] + std::abs(coord(rng));  // else flat on that axis
    const Bounds3f b = box(lo, hi);
    Vec3f o{coord(rng), coord(rng), coord(rng)};
    if (pick(rng) == 0) o = lo;                                    // a corner
    if (pick(rng) == 0) o[pick(rng) % 3] = hi[pick(rng) % 3 == 0 ? 0 : 1];  // sometimes on a face
    Vec3f d{coord(rng), coord(rng), coord(rng)};
    if (pick(rng) < 5) d = 0.5f * (lo + hi) - o;  // aimed at the box's centre
    for (int a = 0; a < 3; ++a)
      if (pick(rng) < 2) d[a] = special[static_cast<size_t>(pick(rng) + (i & 1))];
    if (d == Vec3f{}) d = {0.0f, -0.0f, 1.0f};
    const float tmin = pick(rng) < 2 ? 0.0f : std::abs(coord(rng));
    const float tmaxes[] = {INFINITY, tmin, tmin + 0.5f, 100.0f};
    const Ray ray = make_ray(o, d, tmin, INFINITY);
    const RayBoxTester tester(ray);
    for (float tmax : tmaxes) {
      INFO("case " << i << " tmax " << tmax);
      const bool scalar = tester.hits(b, tmax);
      REQUIRE(tester.hits_sse2(b, tmax) == scalar);
      (scalar ? met : missed) += 1;
    }
  }
  CHECK(met > 7000);
  CHECK(missed > 40000);
}
#endif
