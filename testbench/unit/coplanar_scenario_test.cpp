// The `coplanar` scenario: ties between stacked coplanar triangles are scored
// as the spec says (any tied triangle is correct), in-plane rays expect a miss,
// and the re-hits of duplicates defeat primid and, for the reversed duplicate,
// the validity bit.
#include <catch2/catch.hpp>

#include "scenario_expect_checks.h"
#include "replay/verdict.h"
#include "scenario_test_support.h"

using namespace vbsim;

TEST_CASE("coplanar expectations agree with a brute-force rational search", "[scenario][coplanar]") {
  const auto g = test::generate_scenario("coplanar", 60, 2, {});
  CHECK(test::check_expects_brute_force(g.traces[0], 1) == static_cast<int>(g.cases[0].rays.size()));
}

TEST_CASE("coplanar ties are correct answers and duplicates defeat primid and the sign bit", "[scenario][coplanar]") {
  const auto g = test::generate_scenario("coplanar", 60, 2, {});
  int in_plane = 0, stacked = 0;
  test::visit_outcomes(g.traces[0], "none", [&](const TraceRay& r, const RayOutcome& out, const Scene& scene) {
    if (r.kind != RayKind::Primary) return;
    if (r.d.z == 0.0f) {  // lies in the stack's plane: no triangle is hit
      ++in_plane;
      CHECK(r.expect_prim == -1);
      CHECK(out.verdict == Verdict::Correct);
      return;
    }
    CHECK(out.verdict == Verdict::Correct);
    // Any answer among the exact ties (brute force) is correct, any other
    // triangle of the stack is not: triangles 0, 1, 2 are one triangle, and
    // 4 overlaps it in the same plane, so they tie wherever they overlap.
    const ExactRay intended = intended_ray(r, scene, nullptr);
    const std::vector<int32_t> ties = test::reference_closest(scene, intended).ties;
    stacked += ties.size() >= 3;
    for (int32_t p = 0; p < scene.size(); ++p) {
      const bool tied = std::count(ties.begin(), ties.end(), p) == 1;
      CHECK((judge(r, p, scene, &intended) == Verdict::Correct) == tied);
    }
  });
  CHECK(in_plane == 12);
  CHECK(stacked == 14);  // of 48 camera rays off the plane (seed 2)
  // Children leave the plane: the exact answer is a miss; primid drops only
  // the parent, so a duplicate is re-hit (a self hit: it shares the parent's
  // vertices); the overlapping triangle 4 shares none (a false hit).
  const test::VerdictCounts primid = test::total_counts(test::replay_traces(g.traces, "primid"));
  CHECK(primid.self_hit == 3);
  CHECK(primid.false_hit == 6);
  // The validity bit rejects the same-winding duplicates (equal bits, zero
  // distance) but not the reversed one, met from its other side (bits differ).
  const test::VerdictCounts vb = test::total_counts(test::replay_traces(g.traces, "validity-bit"));
  CHECK(vb.self_hit == 3);
  CHECK(vb.false_hit + vb.missed == 0);
}
