// The `layers` scenario: exact answers checked by brute force, and the light
// leaks it reproduces on a fixed seed: an offset or tmin larger than the gap
// between two surfaces skips the nearer one.
#include <catch2/catch.hpp>

#include "scenario_expect_checks.h"
#include "scenario_test_support.h"

using namespace vbsim;

namespace {

// Seed 2, separations 0.5 and 10 times the default offset 1e-4, 48 camera rays
// (12 per case over the two layer cases, the nested spheres and the sphere on a
// plane). Every camera ray hits the upper surface, so each case holds 12
// refraction, 12 reflection and 12 shadow children.
test::GeneratedScenario small_layers() {
  return test::generate_scenario("layers", 48, 2, {{"separation", "0.5,10"}});
}

std::string trace_named(const test::GeneratedScenario& g, const std::string& name) {
  for (size_t i = 0; i < g.cases.size(); ++i)
    if (g.cases[i].name == name) return g.traces[i];
  FAIL("no case " << name);
  return {};
}

}  // namespace

TEST_CASE("layers expectations agree with a brute-force rational search", "[scenario][layers]") {
  const auto g = small_layers();
  REQUIRE(g.cases.size() == 4);
  int checked = 0;
  for (const std::string& t : g.traces) checked += test::check_expects_brute_force(t, 1);
  CHECK(checked == 4 * 48);
}

TEST_CASE("layers: offsets larger than the gap leak light, smaller ones do not", "[scenario][layers]") {
  const auto g = small_layers();
  const std::vector<std::string> close{trace_named(g, "layers-sep0.5")}, apart{trace_named(g, "layers-sep10")};
  for (const char* method : {"tmin", "offset-normal", "offset-direction"}) {
    INFO(method);
    // A gap of half the offset: every refraction and shadow child (they all go
    // toward the lower square) skips it; the reflections leave upward.
    const test::VerdictCounts c = test::total_counts(test::replay_traces(close, method));
    CHECK(c.missed == 24);
    CHECK(c.self_hit + c.false_hit == 0);
    // Ten times the offset: nothing skipped.
    const test::VerdictCounts a = test::total_counts(test::replay_traces(apart, method));
    CHECK(a.missed + a.self_hit + a.false_hit == 0);
  }
  // The adaptive offset at z = 1 is 256 ulps (3e-5) along the normal, below the 5e-5 gap.
  const test::VerdictCounts ad = test::total_counts(test::replay_traces(close, "offset-adaptive"));
  CHECK(ad.missed + ad.self_hit + ad.false_hit == 0);
}

TEST_CASE("layers: the validity bit keeps a same-facing neighbour unless its epsilon exceeds the gap", "[scenario][layers]") {
  const auto g = small_layers();
  const std::vector<std::string> close{trace_named(g, "layers-sep0.5")};
  // Exponent epsilon at z = 1: 2^-17 (7.6e-6), below the gap: all correct.
  const test::VerdictCounts vb = test::total_counts(test::replay_traces(close, "validity-bit"));
  CHECK(vb.missed + vb.self_hit + vb.false_hit == 0);
  // Fixed epsilon 1e-4, twice the gap: the left pair faces the same way, so a
  // downward child (sign 1) meets the lower square's front (bit 1): a suspect
  // within epsilon, rejected. The right pair is a sheet: the lower square is
  // met from behind (bit 0), never suspect. Half the cameras aim left.
  const test::VerdictCounts fixed = test::total_counts(test::replay_traces(close, "validity-bit", [](ReplayOptions& o) {
    o.method.avoidance.eps_mode = EpsilonMode::Fixed;
    o.method.avoidance.eps = 1e-4f;
  }));
  CHECK(fixed.missed == 12);
  CHECK(fixed.self_hit + fixed.false_hit == 0);
  // sign-only rejects every suspect, whatever the distance.
  const test::VerdictCounts so = test::total_counts(test::replay_traces(close, "sign-only"));
  CHECK(so.missed == 12);
}

TEST_CASE("layers: a fixed offset leaks light under a sphere resting on a plane", "[scenario][layers]") {
  const auto g = small_layers();
  const std::vector<std::string> contact{trace_named(g, "layers-sphere-on-plane")},
      nested{trace_named(g, "layers-nested-spheres")};
  const ReplayStats normal = test::replay_traces(contact, "offset-normal");
  // Grazing reflections off the plane run on toward the contact and meet the
  // sphere's bottom fan (slope 0.098) after about two thirds of their distance
  // to it: for points within ~1e-3 of the contact that hit is nearer than the
  // 1e-4 offset above the plane. On this seed 5 of 12 reflections leak; none
  // of the 12 shadow rays (straight up, where the sphere is 0.098 rho above).
  CHECK(test::kind_counts(normal, RayKind::Reflect).missed == 5);
  CHECK(test::kind_counts(normal, RayKind::Shadow).missed == 0);
  CHECK(test::total_counts(test::replay_traces(contact, "validity-bit")).missed == 0);
  // Nested spheres 4e-5 apart: the inner sphere is skipped by every refraction
  // and shadow child under a 1e-4 offset, and kept by the validity bit.
  CHECK(test::total_counts(test::replay_traces(nested, "offset-normal")).missed == 24);
  CHECK(test::total_counts(test::replay_traces(nested, "validity-bit")).missed == 0);
}
