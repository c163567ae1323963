// The `refraction` scenario: exact answers checked by brute force; every
// transmitted ray that exits the glass meets the far wall from behind (its
// sign bit differs from the wall's front bit), and the validity bit keeps all
// those exit hits.
#include <catch2/catch.hpp>

#include "scenario_expect_checks.h"
#include "scenario_test_support.h"

using namespace vbsim;

namespace {
test::GeneratedScenario small_glass() { return test::generate_scenario("refraction", 40, 4, {}); }
}  // namespace

TEST_CASE("refraction expectations agree with a brute-force rational search", "[scenario][refraction]") {
  const auto g = small_glass();
  REQUIRE(g.traces.size() == 2);
  int checked = 0;
  for (const std::string& t : g.traces) checked += test::check_expects_brute_force(t, 2);
  CHECK(checked > 50);
}

TEST_CASE("refraction: the validity bit keeps every exit hit inside closed glass", "[scenario][refraction]") {
  const auto g = small_glass();
  int inside = 0, suspects_by_sign = 0, kept = 0, none_self = 0;
  for (const std::string& t : g.traces) {
    test::visit_outcomes(t, "validity-bit", [&](const TraceRay& r, const RayOutcome& out, const Scene& scene) {
      CHECK(out.verdict == Verdict::Correct);
      if (r.parent_prim < 0 || r.expect_prim < 0) return;
      // A ray travelling inside the glass: it meets its next wall from behind.
      const bool exits = dot(r.d, geometric_normal(scene.triangles[r.expect_prim])) > 0;
      if (!exits) return;
      ++inside;
      // Both inside children (refraction in, total internal reflection) leave
      // their wall into the glass: sign 1; the exit wall's front bit is 0.
      CHECK(r.sign == 1);
      suspects_by_sign += r.sign == 0;
      kept += out.hit.prim == r.expect_prim;
    });
    test::visit_outcomes(t, "none", [&](const TraceRay&, const RayOutcome& out, const Scene&) {
      none_self += out.verdict == Verdict::SelfHit;
    });
  }
  // Seed 4, 20 camera rays per object, up to 4 transmissions each.
  CHECK(inside == 80);
  CHECK(suspects_by_sign == 0);
  CHECK(kept == inside);
  // Without a method the same rays re-hit their own wall (acne).
  CHECK(none_self == 58);
  const test::VerdictCounts so = test::total_counts(test::replay_traces(g.traces, "sign-only"));
  CHECK(so.missed + so.self_hit + so.false_hit == 0);
}
