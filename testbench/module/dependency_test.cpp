// Child rays wait for their parents: a hand-computed parent and two children on
// one core with one slot, a child before its parent refused, and an emission
// width above one ray a cycle reaching its analytic bound with ideal memory.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>

#include "bench/functional_bench.h"
#include "hw/cycle_replay.h"
#include "replay/replay_run.h"
#include "trace/trace_file.h"
#include "../unit/three_floors.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

struct Logged {
  CycleRunResult result;
  std::map<int64_t, RayTimes> times;  ///< by ray id
};

Logged run_logged(const std::vector<TraceRay>& rays, const Scene& scene, const Bvh& bvh, const HwConfig& cfg) {
  Logged out;
  const RayFeed feed = feed_of(rays);
  CycleRunOptions options;
  options.ray_times = [&](const RayTimes& t) { out.times[t.id] = t; };
  out.result = run_cycle_replay(feed, scene, bvh, ReplayOptions{}, cfg, {}, options);
  return out;
}

/// A child of ray `parent` that leaves like a camera ray from z = 1 (the same search as its parent).
TraceRay child_of(int64_t id, int64_t parent) {
  TraceRay r = down_from(id, 1.0f);
  r.parent = parent;
  r.parent_prim = 0;
  r.kind = RayKind::Reflect;
  r.sign = 0;
  return r;
}

}  // namespace

TEST_CASE("a parent and its two children on one slot: the children wait for the parent's result and the shader",
          "[module][deps]") {
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);  // one emission lane, 1 cycle a ray, no sign-bit cost
  cfg.shader.latency_cycles = 10;
  const Logged run = run_logged({down_from(1, 1.0f), child_of(2, 1), child_of(3, 1)}, f.scene, f.bvh, cfg);
  // Each ray's search: root box 5, two nodes 3 + 5 each, the leaf 3 + 11: 35 cycles.
  //   P:  ready 0, emitted 0-1, dispatched 1, done 36
  //   C1: ready 36 + 10 = 46, emitted 46-47, dispatched 47, done 82
  //   C2: ready 46, emitted 47-48, held for the slot until 82, done 117
  const auto& t = run.times;
  REQUIRE(t.size() == 3);
  CHECK((std::vector<uint64_t>{t.at(1).ready, t.at(1).emitted, t.at(1).started, t.at(1).finished}) ==
        std::vector<uint64_t>{0, 0, 1, 36});
  CHECK((std::vector<uint64_t>{t.at(2).ready, t.at(2).emitted, t.at(2).started, t.at(2).finished}) ==
        std::vector<uint64_t>{46, 46, 47, 82});
  CHECK((std::vector<uint64_t>{t.at(3).ready, t.at(3).emitted, t.at(3).started, t.at(3).finished}) ==
        std::vector<uint64_t>{46, 47, 82, 117});
  CHECK(t.at(3).parent == 1);
  const auto& src = run.result.hw["instances"]["accelerator.ray_source"];
  CHECK(src["children_waited"] == 2);
  CHECK(src["dependency_wait_cycles"] == 2 * (46 - 1));  // both read into the buffer at cycle 1, when P left it
  CHECK(src["lane_idle_dependency_cycles"] == 46 - 1);
  CHECK(src["no_free_slot_cycles"] == 82 - 48);
  CHECK(run.result.counters.cycles == 117);

  // Independent replay: C1 is emitted at once and holds the slot's queue behind P.
  cfg.source.dependencies = false;
  const Logged free = run_logged({down_from(1, 1.0f), child_of(2, 1), child_of(3, 1)}, f.scene, f.bvh, cfg);
  CHECK(free.times.at(2).started == 36);
  CHECK(free.times.at(3).started == 71);
  CHECK(free.result.counters.cycles == 106);
}

TEST_CASE("a child whose parent comes later in the trace is an error naming the child, or with independent "
          "missing parents the parent", "[module][deps]") {
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(run_logged({child_of(2, 7), down_from(7, 1.0f)}, f.scene, f.bvh, cfg),
                    Contains("trace position 0") && Contains("parent 7 of ray 2 is not among the 131072 rays before") &&
                        Contains("--missing-parents independent"));
  cfg.source.missing_parents = MissingParents::Independent;
  CHECK_THROWS_WITH(run_logged({child_of(2, 7), down_from(7, 1.0f)}, f.scene, f.bvh, cfg),
                    Contains("trace position 1") && Contains("ray 7 is the parent of ray 2 (trace position 0)") &&
                        Contains("--deps off"));
  cfg.source.dependencies = false;  // as unrelated queries, the order does not matter
  CHECK(run_logged({child_of(2, 7), down_from(7, 1.0f)}, f.scene, f.bvh, cfg).times.size() == 2);
}

TEST_CASE("a child whose parent is not in the trace is an error, or ready at once and counted", "[module][deps]") {
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);
  CHECK_THROWS_WITH(run_logged({down_from(1, 1.0f), child_of(2, 99)}, f.scene, f.bvh, cfg),
                    Catch::Matchers::Contains("trace position 1: parent 99 of ray 2"));
  cfg.source.missing_parents = MissingParents::Independent;
  const Logged run = run_logged({down_from(1, 1.0f), child_of(2, 99)}, f.scene, f.bvh, cfg);
  CHECK(run.times.at(2).ready == 1);  // read into the buffer when ray 1 had left the lane
  CHECK(run.result.hw["instances"]["accelerator.ray_source"]["parents_not_found"] == 1);
  CHECK(run.result.hw["emission"]["parents_not_found"] == 1);
  CHECK_THAT(run.result.hw["emission"]["first_parent_not_found"].get<std::string>(),
             Catch::Matchers::Contains("trace position 1: parent 99 of ray 2"));
}

TEST_CASE("ray ids off the trace's sequence find their parents as sequential ids do", "[module][deps]") {
  // The source takes a ray's position from its id while the ids run 1, 2, 3, ...
  // and from its id table once one does not; either way each child waits for
  // its own parent, also across the switch and after parents left a small window.
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);
  cfg.shader.latency_cycles = 4;
  cfg.source.window = 2;
  // Parent (by position) of each ray; -1: a camera ray.
  const std::vector<int> parent_at = {-1, 0, 1, -1, 3, 2, 4, -1, 7, 8, 8, -1, 11, 12};
  const auto trace_with = [&](const std::vector<int64_t>& ids) {
    std::vector<TraceRay> rays;
    for (size_t i = 0; i < parent_at.size(); ++i)
      rays.push_back(parent_at[i] < 0 ? down_from(ids[i], 1.0f) : child_of(ids[i], ids[parent_at[i]]));
    return rays;
  };
  std::vector<int64_t> sequential(parent_at.size());
  for (size_t i = 0; i < sequential.size(); ++i) sequential[i] = static_cast<int64_t>(i) + 1;
  std::vector<int64_t> off = sequential;
  off[5] = 500;  // off the sequence from position 5 on: 1..5, 500, 7.., then a lower id and a large one
  off[8] = 0;
  off[12] = 2000000000000;
  const Logged a = run_logged(trace_with(sequential), f.scene, f.bvh, cfg);
  const Logged b = run_logged(trace_with(off), f.scene, f.bvh, cfg);
  const auto& sa = a.result.hw["instances"]["accelerator.ray_source"];
  const auto& sb = b.result.hw["instances"]["accelerator.ray_source"];
  CHECK(sa["children_waited"] > 0);
  CHECK(sa["parents_not_found"] == 0);
  CHECK(sb["children_waited"] == sa["children_waited"]);
  CHECK(sb["parents_not_found"] == 0);
  for (size_t i = 0; i < parent_at.size(); ++i) {
    const RayTimes& ta = a.times.at(sequential[i]);
    const RayTimes& tb = b.times.at(off[i]);
    INFO("position " << i);
    CHECK((std::vector<uint64_t>{ta.ready, ta.emitted, ta.started, ta.finished}) ==
          std::vector<uint64_t>{tb.ready, tb.emitted, tb.started, tb.finished});
    if (parent_at[i] >= 0) CHECK(tb.ready >= b.times.at(off[parent_at[i]]).finished + 4);
  }
}

TEST_CASE("an emission width of several rays a cycle reaches its bound with ideal memory", "[module][deps]") {
  auto src = open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  const SceneAndBvh sb = load_trace_scene(src->header());
  const std::vector<TraceRay> rays = bench_rays(sb.scene, 40000, 3);
  for (const uint32_t width : {2u, 4u}) {
    INFO("rays per cycle " << width);
    HwConfig cfg;
    cfg.cores = 32;
    cfg.slots_per_core = 64;
    cfg.memory.ideal = true;
    cfg.memory.ideal_latency = 4;
    cfg.source = {1, 0, 0};
    cfg.source.rays_per_cycle = width;
    cfg.source.window = 1u << 16;
    cfg.box = {4, 6, 1};
    cfg.triangle = {2, 15, 1};
    const Logged run = run_logged(rays, sb.scene, sb.bvh, cfg);
    const KindStats t = run.result.stats.total();
    REQUIRE(t.rays == rays.size());
    const double n = static_cast<double>(t.rays);
    const double box_per_ray = (n + t.traversal.node_visits) / n, tri_per_ray = t.traversal.triangle_tests / n;
    const double bound = std::min({static_cast<double>(width) / cfg.source.issue_interval,
                                   cfg.cores * cfg.box.count / (cfg.box.issue_interval * box_per_ray),
                                   cfg.cores * cfg.triangle.count / (cfg.triangle.issue_interval * tri_per_ray)});
    // Steady state: the rays finishing between the tenth and the ninetieth
    // percentile of finish cycles (filling and draining left out).
    std::vector<uint64_t> finish;
    for (const auto& [id, times] : run.times) finish.push_back(times.finished);
    std::sort(finish.begin(), finish.end());
    const size_t lo = finish.size() / 10, hi = finish.size() * 9 / 10;
    const double steady = static_cast<double>(hi - lo) / static_cast<double>(finish[hi] - finish[lo]);
    const double overall = n / run.result.counters.cycles;
    INFO("box ops/ray " << box_per_ray << " bound " << bound << " steady " << steady << " overall " << overall);
    CHECK(bound == Approx(width));  // the source is the limit here
    CHECK(overall <= bound * 1.0000001);
    CHECK(steady >= 0.98 * bound);
    CHECK(steady <= bound * 1.02);
  }
}

TEST_CASE("children of one hit with the same origin go through one bundle call of the emission API",
          "[module][deps]") {
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);
  cfg.slots_per_core = 2;
  cfg.shader.latency_cycles = 10;
  cfg.source.bundles = true;
  cfg.source.bundle_cycles = 2;
  const Logged run = run_logged({down_from(1, 1.0f), child_of(2, 1), child_of(3, 1)}, f.scene, f.bvh, cfg);
  // P done at 36; its children ready at 46; one bundle call of 2 + 2 x 1 cycles: both
  // emitted at 46 and dispatched at 50 into the two slots, done 35 cycles later.
  CHECK(run.times.at(2).emitted == 46);
  CHECK(run.times.at(3).emitted == 46);
  CHECK(run.times.at(2).started == 50);
  CHECK(run.times.at(3).started == 50);
  CHECK(run.result.hw["emission"]["bundles"] == 1);
  CHECK(run.result.hw["emission"]["bundled_rays"] == 2);
  // Without bundles: one call each, 46-47 and 47-48.
  cfg.source.bundles = false;
  const Logged single = run_logged({down_from(1, 1.0f), child_of(2, 1), child_of(3, 1)}, f.scene, f.bvh, cfg);
  CHECK(single.times.at(2).started == 47);
  CHECK(single.times.at(3).started == 48);
}
