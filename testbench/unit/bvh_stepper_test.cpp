// The step-wise BVH search against closest_hit(): the same hit, bit for bit,
// and the same work counters, for every ray of the bundled trace and for
// random rays, under several self-intersection methods and on-chip stack
// depths (small depths force spills and refills, which must not change a hit).
#include <catch2/catch.hpp>

#include <cstring>
#include <string>
#include <vector>

#include "bench/functional_bench.h"
#include "datapath/bvh_stepper.h"
#include "datapath/testers.h"
#include "replay/ray_emission.h"
#include "replay/replay_run.h"
#include "trace/trace_file.h"
#include "trace/trace_source.h"

using namespace vbsim;

namespace {

struct StepperRun {
  Hit hit;
  CandidateCounters cc;
  TraversalCounters tc;
  uint64_t spills = 0, refills = 0;
};

/// Drives a stepper through every request until it is done.
StepperRun run_stepper(BvhStepper<ThreeHalfPlaneTester>& s, const Ray& ray, bool any_hit) {
  StepperRun r;
  StepRequest q = s.begin(ray, any_hit, r.cc, r.tc);
  for (int guard = 0; q.kind != StepRequest::Done; ++guard) {
    REQUIRE(guard < 1000000);
    if (q.kind == StepRequest::Node) {
      q = s.node_step();
    } else if (q.kind == StepRequest::Refill) {
      q = s.refilled();
    } else {
      for (uint32_t i = q.index; i < q.index + q.count; ++i)
        if (s.triangle_step(i).stop) break;
      q = s.leaf_done();
    }
  }
  r.hit = s.hit();
  r.spills = s.spills();
  r.refills = s.refills();
  return r;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct Totals {
  uint64_t rays = 0, spills = 0, refills = 0;
};

/// Compares stepper and closest_hit on `ray`; adds the stepper's overflow counts to `t`.
void check_ray(const Bvh& bvh, const CandidateFilter& filter, BvhStepper<ThreeHalfPlaneTester>& stepper,
               const Ray& ray, bool any_hit, Totals& t) {
  CandidateCounters cc;
  TraversalCounters tc;
  const Hit want = closest_hit<ThreeHalfPlaneTester>(bvh, ray, filter, cc, tc, any_hit);
  const StepperRun got = run_stepper(stepper, ray, any_hit);
  REQUIRE(got.hit.prim == want.prim);
  REQUIRE(same_bits(got.hit.t, want.t));
  REQUIRE(same_bits(got.hit.u, want.u));
  REQUIRE(same_bits(got.hit.v, want.v));
  REQUIRE(got.hit.front == want.front);
  REQUIRE(got.cc.candidates == cc.candidates);
  REQUIRE(got.cc.suspects == cc.suspects);
  REQUIRE(got.cc.rejected == cc.rejected);
  REQUIRE(got.tc.node_visits == tc.node_visits);
  REQUIRE(got.tc.box_tests == tc.box_tests);
  REQUIRE(got.tc.triangle_tests == tc.triangle_tests);
  ++t.rays;
  t.spills += got.spills;
  t.refills += got.refills;
}

const SceneAndBvh& bunny() {
  static const SceneAndBvh sb = [] {
    auto src = open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
    return load_trace_scene(src->header());
  }();
  return sb;
}

}  // namespace

TEST_CASE("stepper gives closest_hit's hit on every ray of the bundled trace", "[stepper]") {
  const SceneAndBvh& sb = bunny();
  const std::string method = GENERATE(as<std::string>{}, "none", "validity-bit", "primid", "tmin", "offset-adaptive",
                                      "offset-normal", "sign-only");
  const int depth = GENERATE(1, 3, 16, 128);
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method(method, opt.method, err));
  const CandidateFilter filter(opt.method);
  BvhStepper<ThreeHalfPlaneTester> stepper(sb.bvh, filter, depth);
  auto src = open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  ParentRays parents;
  Totals t;
  TraceRay tr;
  while (src->next(tr)) {
    const EmittedRay er = emit_ray(tr, sb.scene, opt, &parents);
    parents[tr.id] = {tr.o, tr.d};
    INFO(method << " depth " << depth << " ray " << tr.id);
    check_ray(sb.bvh, filter, stepper, er.ray, tr.kind == RayKind::Shadow, t);
  }
  CHECK(t.rays == 1008);
  INFO("BVH depth " << sb.bvh.depth);
  if (depth < 4) {  // the bunny's BVH is deeper than that: overflow must have happened
    CHECK(t.spills > 0);
    CHECK(t.refills > 0);
  }
  if (depth == 128) CHECK(t.spills == 0);
}

TEST_CASE("stepper gives closest_hit's hit on random rays", "[stepper]") {
  const SceneAndBvh& sb = bunny();
  const std::vector<TraceRay> rays = bench_rays(sb.scene, 3000, 7);
  const int depth = GENERATE(2, 16);
  const CandidateFilter filter(SelfIntersectionMethod{});
  BvhStepper<ThreeHalfPlaneTester> stepper(sb.bvh, filter, depth);
  Totals t;
  uint64_t hits = 0;
  for (const TraceRay& tr : rays) {
    Ray r;
    r.o = tr.o;
    r.d = tr.d;
    check_ray(sb.bvh, filter, stepper, r, false, t);
    hits += stepper.hit().prim >= 0;
  }
  CHECK(hits > 300);  // the comparison covered real hits, not only misses
  if (depth == 2) CHECK(t.spills > 0);
}
