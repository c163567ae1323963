// The intersect() contract of testers.h, as checks any tester must pass. Each
// tester's test file runs them in its own TEST_CASEs.
#pragma once
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "datapath/testers.h"
#include "tester_test_support.h"

namespace vbsim::test {

constexpr float kInf = std::numeric_limits<float>::infinity();

template <class Tester>
bool shoot(const Triangle& tri, Vec3f o, Vec3f d, Hit& hit, float tmin = 0.0f, float tmax = kInf) {
  Ray ray;
  ray.o = o;
  ray.d = d;
  ray.tmin = tmin;
  return Tester(ray).intersect(tri, tmax, hit);
}

/// t, u, v and front exactly as worked out by hand; hit.prim is left alone.
template <class Tester>
void check_hand_computed_hits() {
  for (const HandCase& c : hand_computed_cases()) {
    INFO(c.name);
    Hit hit;
    hit.prim = 7;
    REQUIRE(shoot<Tester>(c.tri, c.o, c.d, hit));
    CHECK(hit.t == c.t);
    CHECK(hit.u == c.u);
    CHECK(hit.v == c.v);
    CHECK(int(hit.front) == int(c.front));
    CHECK(hit.prim == 7);
  }
}

/// Rays straight down onto the right triangle (0,0,0) (1,0,0) (0,1,0) just
/// outside each edge miss; the same distance inside hits, and so do rays exactly
/// through an edge or a vertex (the triangle is closed; all arithmetic is exact here).
template <class Tester>
void check_edges_and_outside() {
  const Triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const Vec3f down{0, 0, -1};
  const float e = 1.0f / 1024;
  const Vec3f outside[] = {{0.5f, -e, 1},          {-e, 0.5f, 1},      {0.5f + e, 0.5f, 1},
                           {1 + e, 0, 1},          {-e, -e, 1},        {0, 1 + e, 1},
                           {2, 2, 1},              {-0.5f, 3, 1}};
  const Vec3f inside[] = {{0.5f, e, 1}, {e, 0.5f, 1}, {0.5f - e, 0.5f, 1}, {e, e, 1}};
  for (const Vec3f& o : outside) {
    INFO("outside at " << o.x << ", " << o.y);
    Hit hit;
    CHECK_FALSE(shoot<Tester>(tri, o, down, hit));
  }
  const Vec3f on_boundary[] = {{0.5f, 0, 1}, {0, 0.5f, 1}, {0.5f, 0.5f, 1},
                               {0, 0, 1},    {1, 0, 1},    {0, 1, 1}};
  for (const Vec3f& o : on_boundary) {
    INFO("on the boundary at " << o.x << ", " << o.y);
    Hit hit;
    CHECK(shoot<Tester>(tri, o, down, hit));
  }
  for (const Vec3f& o : inside) {
    INFO("inside at " << o.x << ", " << o.y);
    Hit hit;
    CHECK(shoot<Tester>(tri, o, down, hit));
  }
  Hit hit;
  CHECK_FALSE(shoot<Tester>(tri, {0.25f, 0.25f, 1}, {0, 0, 1}, hit));  // triangle behind the origin
}

/// The interval is open at both ends: exact hits at t = 2 and t = 4 sit on the bounds.
template <class Tester>
void check_open_interval() {
  for (const HandCase& c : hand_computed_cases()) {
    INFO(c.name << " at t = " << c.t);
    Hit hit;
    CHECK_FALSE(shoot<Tester>(c.tri, c.o, c.d, hit, 0.0f, c.t));
    CHECK(shoot<Tester>(c.tri, c.o, c.d, hit, 0.0f, std::nextafter(c.t, kInf)));
    CHECK_FALSE(shoot<Tester>(c.tri, c.o, c.d, hit, c.t, kInf));
    CHECK(shoot<Tester>(c.tri, c.o, c.d, hit, std::nextafter(c.t, 0.0f), kInf));
    CHECK(hit.t > std::nextafter(c.t, 0.0f));
  }
}

/// Rays inside the triangle's plane, through its interior, are not hit.
template <class Tester>
void check_rays_in_plane() {
  Hit hit;
  const Triangle flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  CHECK_FALSE(shoot<Tester>(flat, {-1, 0.25f, 0}, {1, 0, 0}, hit));
  CHECK_FALSE(shoot<Tester>(flat, {-1, -1, 0}, {1, 1.5f, 0}, hit));
  CHECK_FALSE(shoot<Tester>(flat, {0.25f, 0.25f, 0}, {0, -1, 0}, hit));
  // The plane x + y = 1: vertices (1,0,0) (0,1,0) (0,1,1); the ray (2-t, t-1, t/4)
  // stays in it and crosses the triangle (0 <= z <= y <= 1) for 4/3 <= t <= 2.
  const Triangle tilted{{1, 0, 0}, {0, 1, 0}, {0, 1, 1}};
  CHECK_FALSE(shoot<Tester>(tilted, {2, -1, 0}, {-1, 1, 0.25f}, hit));
  // Control: the same triangle from off the plane is hit.
  CHECK(shoot<Tester>(tilted, {2, 2, 0.25f}, {-1, -1, 0}, hit));
}

/// front == (dot(d, Ng) < 0), dot computed separately in double, on random hits
/// from both sides.
template <class Tester>
void check_front_bit_on_random_rays(uint32_t seed) {
  RandomGeometry random(seed);
  int front = 0, back = 0;
  for (int i = 0; i < 20000; ++i) {
    const Triangle tri = random.triangle();
    Vec3f o, d;
    random.ray_towards(tri, o, d);
    const ReferenceHit ref = reference_intersect(tri, o, d);
    if (std::fabs(ref.cosine) < 1e-3) continue;
    Hit hit;
    if (!shoot<Tester>(tri, o, d, hit)) continue;
    const double facing = reference_facing(tri, d);
    INFO("case " << i << " dot(d, Ng) = " << facing);
    REQUIRE(int(hit.front) == (facing < 0.0 ? 1 : 0));
    (hit.front ? front : back) += 1;
  }
  CHECK(front > 2000);
  CHECK(back > 2000);
}

/// Hit or miss as the double reference says, and t to relative 1e-5, on rays that
/// pass more than 1e-4 (in barycentrics) from every edge and not at grazing angles
/// (|cos(d, Ng)| > 0.01). u and v to 5e-4 absolute: their float error grows with
/// |o - v0| |d| / |det| (worst seen: 1.8e-4 for Möller–Trumbore, 4e-5 for the
/// three-half-plane tester), while a swapped or mis-mapped barycentric is off by ~0.1.
template <class Tester>
void check_agreement_with_reference(uint32_t seed) {
  RandomGeometry random(seed);
  int hits = 0, misses = 0;
  double worst_t = 0, worst_uv = 0;
  for (int i = 0; i < 20000; ++i) {
    const Triangle tri = random.triangle();
    Vec3f o, d;
    random.ray_towards(tri, o, d);
    const ReferenceHit ref = reference_intersect(tri, o, d);
    if (ref.edge_distance <= 1e-4 || std::fabs(ref.cosine) <= 0.01 || std::fabs(ref.t) <= 1e-3)
      continue;
    Hit hit;
    const bool got = shoot<Tester>(tri, o, d, hit);
    INFO("case " << i << " reference t " << ref.t << " u " << ref.u << " v " << ref.v);
    REQUIRE(got == ref.hit);
    if (!got) {
      ++misses;
      continue;
    }
    ++hits;
    const double t_error = std::fabs(hit.t - ref.t) / ref.t;
    const double uv_error = std::max(std::fabs(hit.u - ref.u), std::fabs(hit.v - ref.v));
    REQUIRE(t_error <= 1e-5);
    REQUIRE(uv_error <= 5e-4);
    worst_t = std::max(worst_t, t_error);
    worst_uv = std::max(worst_uv, uv_error);
  }
  WARN("agreement: " << hits << " hits, " << misses << " misses; worst relative t error "
                     << worst_t << ", worst u/v error " << worst_uv);
  CHECK(hits > 3000);
  CHECK(misses > 3000);
}

}  // namespace vbsim::test
