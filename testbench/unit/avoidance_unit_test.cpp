// The intersection-avoidance unit's decision logic on hand-computed cases.
#include <catch2/catch.hpp>

#include <cmath>

#include "datapath/avoidance_unit.h"

using namespace vbsim;

namespace {
// Triangle in the plane z = 0, Ng = (0, 0, +1) (counter-clockwise seen from +z).
const Triangle kFloor{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

Ray ray_from(Vec3f o, Vec3f d, uint8_t sign) {
  Ray r;
  r.o = o;
  r.d = d;
  r.sign = sign;
  return r;
}

Hit hit_at(float t, uint8_t front) {
  Hit h;
  h.prim = 0;
  h.t = t;
  h.front = front;
  return h;
}
}  // namespace

TEST_CASE("exponent epsilon follows the largest vertex exponent with guard band and minimum",
          "[avoidance]") {
  AvoidanceConfig cfg;
  cfg.eps_mode = EpsilonMode::Exponent;
  cfg.guard_bits = 5;
  cfg.min_exponent = 110;
  // Largest coordinate 1.0: biased exponent 127; 127 - 23 + 5 = 109 < 110 -> 2^(110-127).
  CHECK(avoidance_epsilon(cfg, kFloor) == std::ldexp(1.0f, -17));
  // Largest coordinate 2^20 (biased 147): 147 - 18 = 129 -> 2^2 = 4 (32 ulps of 2^20).
  const Triangle far{{1048576.0f, 0, 0}, {1048577.0f, 0, 0}, {1048576.0f, 1, 0}};
  CHECK(avoidance_epsilon(cfg, far) == 4.0f);
  // Negative coordinates count by magnitude.
  const Triangle neg{{-3000.0f, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // 3000: biased exponent 138
  CHECK(avoidance_epsilon(cfg, neg) == std::ldexp(1.0f, 138 - 18 - 127));
  cfg.eps_mode = EpsilonMode::Fixed;
  cfg.eps = 0.25f;
  CHECK(avoidance_epsilon(cfg, far) == 0.25f);
}

TEST_CASE("differing sign and front/back bits are never suspect", "[avoidance]") {
  AvoidanceConfig cfg;
  cfg.policy = AvoidancePolicy::SignOnly;
  // Ray leaving the floor upward (sign 0) meets a candidate from the front (bit 1).
  const auto dec = avoidance_decide(cfg, ray_from({0.2f, 0.2f, 1e-9f}, {0, 0, -1}, 0), kFloor, hit_at(1e-9f, 1));
  CHECK_FALSE(dec.suspect);
  CHECK_FALSE(dec.reject);
}

TEST_CASE("a re-hit of the parent plane from just below is rejected by policy all", "[avoidance]") {
  AvoidanceConfig cfg;
  cfg.eps_mode = EpsilonMode::Fixed;
  cfg.eps = 1e-4f;
  // Origin 1e-7 below the floor, ray going up through it: dot(d, Ng) > 0 -> sign 0,
  // and the candidate is met from the back -> front 0: suspect.
  const Ray r = ray_from({0.2f, 0.2f, -1e-7f}, {0, 0, 1}, 0);
  const auto dec = avoidance_decide(cfg, r, kFloor, hit_at(1e-7f, 0));
  CHECK(dec.suspect);
  CHECK(dec.invalid == (AvoidanceDecision::kTestNormal | AvoidanceDecision::kTestRay));
  CHECK(dec.reject);
}

TEST_CASE("a far suspect is kept: the epsilon tests say valid", "[avoidance]") {
  AvoidanceConfig cfg;
  cfg.eps_mode = EpsilonMode::Fixed;
  cfg.eps = 1e-4f;
  const Ray r = ray_from({0.2f, 0.2f, -0.5f}, {0, 0, 1}, 0);
  const auto dec = avoidance_decide(cfg, r, kFloor, hit_at(0.5f, 0));
  CHECK(dec.suspect);
  CHECK(dec.invalid == 0);
  CHECK_FALSE(dec.reject);
}

TEST_CASE("policies differ on a grazing re-hit: all keeps it, vote and sign-only reject it",
          "[avoidance]") {
  AvoidanceConfig cfg;
  cfg.eps_mode = EpsilonMode::Fixed;
  cfg.eps = 1e-4f;
  // 1e-7 below the plane, leaving at slope 1e-4: the plane is 1e-3 away along the ray.
  const Ray r = ray_from({0.2f, 0.2f, -1e-7f}, {1, 0, 1e-4f}, 0);
  const Hit h = hit_at(1e-3f, 0);
  cfg.policy = AvoidancePolicy::All;
  auto dec = avoidance_decide(cfg, r, kFloor, h);
  CHECK(dec.invalid == AvoidanceDecision::kTestNormal);
  CHECK_FALSE(dec.reject);
  cfg.policy = AvoidancePolicy::Vote;  // normal weight 2 of 3 enabled weight: reject
  CHECK(avoidance_decide(cfg, r, kFloor, h).reject);
  cfg.policy = AvoidancePolicy::SignOnly;
  CHECK(avoidance_decide(cfg, r, kFloor, h).reject);
  // Vote with the normal test saying valid but ray and component saying invalid:
  // weights 1 + 1 of 4 reach half: reject.
  cfg.policy = AvoidancePolicy::Vote;
  cfg.test_component = true;
  const Ray above = ray_from({0.2f, 0.2f, 0.5f}, {0, 0, -1}, 0);  // far from the plane
  dec = avoidance_decide(cfg, above, kFloor, hit_at(1e-6f, 0));
  CHECK(dec.invalid == (AvoidanceDecision::kTestRay | AvoidanceDecision::kTestComponent));
  CHECK(dec.reject);
  // Only the ray test: 1 of 4 is not half: keep.
  cfg.test_component = false;
  dec = avoidance_decide(cfg, above, kFloor, hit_at(1e-6f, 0));
  CHECK(dec.invalid == AvoidanceDecision::kTestRay);
  CHECK_FALSE(dec.reject);
}

TEST_CASE("component test approximates the ray test with a box inside its sphere", "[avoidance]") {
  AvoidanceConfig cfg;
  cfg.eps_mode = EpsilonMode::Fixed;
  cfg.eps = 1.0f;
  cfg.test_normal = false;
  cfg.test_ray = false;
  cfg.test_component = true;
  const Ray r = ray_from({0, 0, 5}, {1, 1, 1}, 0);
  // Displacement (0.5, 0.5, 0.5): each < 0.577 -> invalid.
  CHECK(avoidance_decide(cfg, r, kFloor, hit_at(0.5f, 0)).reject);
  // Displacement (0.6, 0.6, 0.6): outside the box (though |.| = 1.04 is also outside the sphere).
  CHECK_FALSE(avoidance_decide(cfg, r, kFloor, hit_at(0.6f, 0)).reject);
}
