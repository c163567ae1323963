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
#include "scene/bvh_collapse.h"
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
  REQUIRE(got.tc.stack_pushes == tc.stack_pushes);
  REQUIRE(got.tc.stack_pops == tc.stack_pops);
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
    const EmittedRay er = emit_ray(tr, sb.scene, opt, find_parent(parents, tr.parent));
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

namespace {

/// The stepper against closest_hit() on 3,000 random rays of the bunny over
/// `bvh` (closest hits, and any hits too when `any_too`); the overflow counts.
Totals random_rays(const Bvh& bvh, int depth, bool any_too) {
  const std::vector<TraceRay> rays = bench_rays(bunny().scene, 3000, 7);
  const CandidateFilter filter(SelfIntersectionMethod{});
  BvhStepper<ThreeHalfPlaneTester> stepper(bvh, filter, depth);
  Totals t;
  uint64_t hits = 0;
  for (const TraceRay& tr : rays) {
    Ray r;
    r.o = tr.o;
    r.d = tr.d;
    check_ray(bvh, filter, stepper, r, false, t);
    hits += stepper.hit().prim >= 0;
    if (any_too) check_ray(bvh, filter, stepper, r, true, t);
  }
  CHECK(hits > 300);  // the comparison covered real hits, not only misses
  return t;
}

}  // namespace

TEST_CASE("stepper gives closest_hit's hit on random rays", "[stepper]") {
  const int depth = GENERATE(2, 16);
  const Totals t = random_rays(bunny().bvh, depth, false);
  if (depth == 2) CHECK(t.spills > 0);
}

TEST_CASE("stepper gives closest_hit's hit and work over 4- and 8-wide trees", "[stepper][wide]") {
  const int width = GENERATE(4, 8);
  const int depth = GENERATE(2, 16);
  Bvh bvh = bunny().bvh;
  collapse_bvh(bvh, width);
  const Totals t = random_rays(bvh, depth, true);
  if (depth == 2) CHECK(t.spills > 0);  // several pushes a node: spills and refills too
  if (depth == 2) CHECK(t.refills > 0);
}

namespace {

Bounds3f slab_box(float x_lo, float x_hi) {
  Bounds3f b;
  b.lo = {x_lo, -1, -1};
  b.hi = {x_hi, 1, 1};
  return b;
}

/// A triangle in the plane x = `x` beside the x axis (y from 0.5 to 0.9): a ray
/// along the axis meets its leaf's box but never the triangle.
BvhTriangle beside_axis(float x, uint32_t prim) { return {{{x, 0.5f, -0.5f}, {x, 0.9f, -0.5f}, {x, 0.5f, 0.5f}}, prim}; }

/// A comb of `n` interior nodes along +x. Node k: child 0 is node k + 1 (the
/// last node's child 0 is the leaf of triangle n), box x in [1, 2], entered at
/// t = 1; child 1 is the leaf of triangle k, box x in [50 + k, 51 + k], entered
/// at t = 50 + k. A ray from the origin along +x meets both children of every
/// node and no triangle, so it descends the comb pushing one entry per node,
/// then pops and visits the n side leaves, last pushed first.
Bvh comb_bvh(uint32_t n) {
  Bvh bvh;
  for (uint32_t k = 0; k < n; ++k) {
    BvhNode node{};
    node.set_child(0, slab_box(1, 2), k + 1 < n ? BvhRef{k + 1, 0} : BvhRef{n, 1});
    node.set_child(1, slab_box(50.0f + k, 51.0f + k), BvhRef{k, 1});
    bvh.nodes.push_back(node);
    bvh.tris.push_back(beside_axis(50.5f + k, k));
  }
  bvh.tris.push_back(beside_axis(1.5f, n));
  bvh.root_bounds = slab_box(1, 51.0f + n);
  bvh.root = BvhRef{0, 0};
  bvh.depth = static_cast<int>(n) + 1;
  return bvh;
}

}  // namespace

// 10 pushes onto 3 on-chip entries: the pushes 4 to 10 each spill the oldest
// entry (7 spills). The pops take the 3 on-chip entries (side leaves 9, 8, 7),
// then refill the top 3 of the 7 spilled (stack entries 4..6), pop them (6, 5,
// 4), refill 3 more (1..3), pop them, refill the last one (entry 0) and pop it:
// 3 refills of 3, 3 and 1 entries.
TEST_CASE("stepper spills and refills a hand-built comb exactly", "[stepper]") {
  const uint32_t n = 10;
  const Bvh bvh = comb_bvh(n);
  const CandidateFilter filter(SelfIntersectionMethod{});
  BvhStepper<ThreeHalfPlaneTester> stepper(bvh, filter, 3);
  Ray ray;
  ray.o = {0, 0, 0};
  ray.d = {1, 0, 0};
  CandidateCounters cc;
  TraversalCounters tc;
  std::vector<std::string> seen;
  StepRequest q = stepper.begin(ray, false, cc, tc);
  while (q.kind != StepRequest::Done && seen.size() < 100) {
    if (q.kind == StepRequest::Node) {
      seen.push_back("N" + std::to_string(q.index));
      q = stepper.node_step();
    } else if (q.kind == StepRequest::Refill) {
      seen.push_back("R" + std::to_string(q.index) + "+" + std::to_string(q.count));
      q = stepper.refilled();
    } else {
      seen.push_back("L" + std::to_string(q.index));
      REQUIRE(q.count == 1);
      CHECK_FALSE(stepper.triangle_step(q.index).candidate);
      q = stepper.leaf_done();
    }
  }
  const std::vector<std::string> want = {"N0", "N1", "N2", "N3", "N4", "N5",    "N6", "N7", "N8",
                                         "N9", "L10", "L9", "L8", "L7", "R4+3", "L6", "L5", "L4",
                                         "R1+3", "L3", "L2", "L1", "R0+1", "L0"};
  CHECK(seen == want);
  CHECK(stepper.spills() == 7);
  CHECK(stepper.refills() == 3);
  CHECK(stepper.hit().prim < 0);
  CHECK(tc.node_visits == n);
  CHECK(tc.box_tests == 1 + 2 * n);
  CHECK(tc.triangle_tests == n + 1);
  // Every node meets both children: one push each, and the search pops them all.
  CHECK(tc.stack_pushes == n);
  CHECK(tc.stack_pops == n);
  CandidateCounters fcc;
  TraversalCounters ftc;
  closest_hit<ThreeHalfPlaneTester>(bvh, ray, filter, fcc, ftc);
  CHECK(ftc.stack_pushes == n);
  CHECK(ftc.stack_pops == n);

  // The same comb with the whole stack on chip: nothing spills or refills.
  BvhStepper<ThreeHalfPlaneTester> deep(bvh, filter, 16);
  const StepperRun r = run_stepper(deep, ray, false);
  CHECK(r.spills == 0);
  CHECK(r.refills == 0);
  CHECK(r.tc.node_visits == n);
}
