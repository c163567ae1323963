// Verdicts on hand-built answers: every row of the trace spec's verdict table,
// decided exactly (ties, nearer, farther, not met).
#include <catch2/catch.hpp>

#include "exact/oracle.h"
#include "replay/verdict.h"

using namespace vbsim;

namespace {

// Squares' halves stacked along +z above the parent triangle 0 (z = 0).
Triangle at_z(float z, float x0 = 0) { return {{x0, 0, z}, {x0 + 4, 0, z}, {x0, 4, z}}; }

Scene stack_scene() {
  Triangle neighbour = at_z(0.5f);
  neighbour.v0 = {0, 0, 0};  // shares a vertex position with the parent, reaches z = 0.5
  return make_scene({
      at_z(0),          // 0: parent
      at_z(1),          // 1: the exact answer of the ray below (t = 1)
      at_z(2),          // 2: farther
      at_z(1),          // 3: duplicate of 1: a tie
      at_z(0.5f, -0.5f),  // 4: nearer, unrelated to the parent
      neighbour,        // 5: nearer plane region, shares a vertex with the parent
      at_z(0.5f, 50),   // 6: off to the side: the ray never meets it
  });
}

TraceRay child(int32_t expect) {
  TraceRay tr;
  tr.id = 1;
  tr.kind = RayKind::Reflect;
  tr.o = {0.5f, 0.5f, -1e-7f};  // rounded just below the parent; intended origin (0.5, 0.5, 0)
  tr.d = {0, 0, 1};
  tr.parent_prim = 0;
  tr.has_expect = true;
  tr.expect_prim = expect;
  return tr;
}

Verdict verdict_of(const Scene& scene, const TraceRay& tr, int32_t answer) {
  if (!verdict_needs_exact(tr, answer)) return judge(tr, answer, scene, nullptr);
  const ExactRay intended = intended_ray(tr, scene, nullptr);
  return judge(tr, answer, scene, &intended);
}

}  // namespace

TEST_CASE("verdicts of non-shadow answers follow the spec's table", "[verdict]") {
  const Scene scene = stack_scene();
  const TraceRay tr = child(1);
  CHECK(verdict_of(scene, tr, 1) == Verdict::Correct);
  CHECK(verdict_of(scene, tr, 3) == Verdict::Correct);   // tied with the exact answer
  CHECK(verdict_of(scene, tr, 2) == Verdict::Missed);    // farther
  CHECK(verdict_of(scene, tr, -1) == Verdict::Missed);   // a miss
  CHECK(verdict_of(scene, tr, 4) == Verdict::FalseHit);  // nearer, unrelated
  CHECK(verdict_of(scene, tr, 5) == Verdict::SelfHit);   // nearer, shares a vertex with the parent
  CHECK(verdict_of(scene, tr, 0) == Verdict::SelfHit);   // the parent itself (not met exactly)
  CHECK(verdict_of(scene, tr, 6) == Verdict::FalseHit);  // a triangle the intended ray does not meet
  const TraceRay miss = child(-1);
  CHECK(verdict_of(scene, miss, -1) == Verdict::Correct);
  CHECK(verdict_of(scene, miss, 2) == Verdict::FalseHit);  // any hit where the answer is a miss
  CHECK(verdict_of(scene, miss, 0) == Verdict::SelfHit);
  const TraceRay inconsistent = child(6);  // expects a triangle the ray cannot meet
  CHECK(verdict_of(scene, inconsistent, 1) == Verdict::Unscored);
}

TEST_CASE("shadow verdicts score visibility only", "[verdict]") {
  const Scene scene = stack_scene();
  TraceRay tr = child(1);
  tr.kind = RayKind::Shadow;
  CHECK(verdict_of(scene, tr, 2) == Verdict::Correct);  // occluded by another triangle: still occluded
  CHECK(verdict_of(scene, tr, -1) == Verdict::Missed);  // a light leak
  tr.expect_prim = -1;
  CHECK(verdict_of(scene, tr, -1) == Verdict::Correct);
  CHECK(verdict_of(scene, tr, 0) == Verdict::SelfHit);   // acne
  CHECK(verdict_of(scene, tr, 4) == Verdict::FalseHit);
}
