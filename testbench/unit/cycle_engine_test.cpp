// The cycle-level model: exact cycle counts on hand-built BVHs (one core, one
// slot, ideal memory), throughput against the analytic bound, and the
// SystemC clock agreeing with the engine's cycle count.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <vector>

#include "bench/functional_bench.h"
#include "hw/cycle_replay.h"
#include "hw/memory/bvh_address_map.h"
#include "reduced_precision/reduced_precision_units.h"
#include "replay/replay_run.h"
#include "scene/bvh_collapse.h"
#include "three_floors.h"
#include "trace/trace_file.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

struct Finished {
  int32_t prim;
  uint64_t cycle;
};

struct Run {
  CycleRunResult result;
  std::map<int64_t, Finished> rays;  ///< by ray id
};

/// The validity-bit method's options, as the hand-computed cases use it.
ReplayOptions validity_bit_options() {
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method("validity-bit", opt.method, err));
  return opt;
}

Run run_rays(const std::vector<TraceRay>& rays, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
             const HwConfig& cfg) {
  Run run;
  const RayFeed feed = feed_of(rays);
  const RayResultSink sink = [&](const TraceRay& tr, const RayOutcome& out, uint64_t cycle, uint64_t) {
    run.rays[tr.id] = {out.hit.prim, cycle};
  };
  CycleRunOptions options;
  options.track_parents = false;
  run.result = run_cycle_replay(feed, scene, bvh, opt, cfg, sink, options);
  return run;
}

}  // namespace

TEST_CASE("cycle count of each ray equals the hand-computed sum on a three-node BVH", "[cycle]") {
  const ThreeFloors f;
  const uint32_t M = 3, Lb = 5, Lt = 11, La = 7;
  const ReplayOptions opt = validity_bit_options();
  // Ray A, a camera ray from z = 1: root box, node 0, node 1, leaf [prim 0]:
  // a hit at t = 1, front face; sign 0, so no suspect. Leaves [prim 1] and
  // [prim 2] were pushed but are farther than the hit: popped and skipped.
  TraceRay a = down_from(1, 1.0f);
  // Ray B leaves prim 0 (origin 1e-7 above it, sign bit 1 given): prim 0 is a
  // suspect at t = 1e-7 and the avoidance unit rejects it (closer than the
  // exponent epsilon 2^-17); the search goes on to leaf [prim 1], another
  // suspect, which the unit accepts (1 away from the plane).
  TraceRay b = down_from(2, 1e-7f);
  b.parent = 1;
  b.parent_prim = 0;
  b.kind = RayKind::Reflect;
  b.sign = 1;
  HwConfig independent = one_slot(M, Lb, Lt, La);
  independent.source.dependencies = false;  // B is emitted at once, not after A's result (dependency_test.cpp)
  const Run run = run_rays({a, b}, f.scene, f.bvh, opt, independent);
  REQUIRE(run.rays.at(1).prim == 0);
  REQUIRE(run.rays.at(2).prim == 1);

  // The source emits A in 1 cycle (issue interval 1): dispatched at cycle 1.
  const uint64_t latency_a = Lb            // root box test
                             + (M + Lb)    // node 0: fetch, both child boxes
                             + (M + Lb)    // node 1
                             + (M + Lt);   // leaf [prim 0]: fetch, triangle test
  const uint64_t finish_a = 1 + latency_a;
  // B was emitted at cycle 2 and waited for the only slot: dispatched when A finished.
  const uint64_t latency_b = Lb + (M + Lb) + (M + Lb)
                             + (M + Lt + La)   // leaf [prim 0]: suspect, rejected
                             + (M + Lt + La);  // leaf [prim 1]: suspect, accepted
  CHECK(run.rays.at(1).cycle == finish_a);
  CHECK(run.rays.at(2).cycle == finish_a + latency_b);
  const HwCounters& c = run.result.counters;
  CHECK(c.cycles == finish_a + latency_b);
  CHECK(c.box.ops == 6);
  CHECK(c.triangle.ops == 3);
  CHECK(c.avoidance.ops == 2);
  CHECK(c.no_free_slot_cycles == finish_a - 2);
  CHECK(c.memory_wait_cycles == 7 * M);
  CHECK(c.latency_min == latency_a);
  CHECK(c.latency_max == latency_b);
}

TEST_CASE("a root leaf's triangle tests issue at the pipeline's issue interval", "[cycle]") {
  // No nodes: the root is one leaf of three floors; the ray meets all three.
  const ThreeFloorsLeaf leaf;
  const Scene& scene = leaf.scene;
  const Bvh& bvh = leaf.bvh;
  const uint32_t M = 4, Lb = 2, Lt = 9, interval = 3;
  HwConfig cfg = one_slot(M, Lb, Lt, 1);
  cfg.triangle.issue_interval = interval;
  cfg.source.issue_interval = 5;  // the ray is dispatched at cycle 5
  const Run run = run_rays({down_from(7, 1.0f)}, scene, bvh, ReplayOptions{}, cfg);
  REQUIRE(run.rays.at(7).prim == 0);
  // Root box, leaf fetch, then tests at R, R + 3, R + 6: the last result at R + 6 + Lt.
  CHECK(run.rays.at(7).cycle == 5 + Lb + M + 2 * interval + Lt);
  CHECK(run.result.counters.triangle.wait_cycles == 2 * (interval - 1));
}

TEST_CASE("SystemC time of a run is its cycle count times the clock period", "[cycle]") {
  const ThreeFloors f;
  HwConfig cfg = one_slot(2, 3, 4, 5);
  cfg.clock_mhz = 250;  // 4000 ps
  std::vector<TraceRay> rays;
  for (int i = 0; i < 20; ++i) rays.push_back(down_from(i, 1.0f + i));
  const uint32_t quantum = GENERATE(1u, 7u, 1000u);
  cfg.quantum_cycles = quantum;
  const Run run = run_rays(rays, f.scene, f.bvh, ReplayOptions{}, cfg);
  const nlohmann::json& sc = run.result.hw["systemc"];
  const uint64_t cycles = run.result.counters.cycles;
  INFO("quantum " << quantum);
  CHECK(cycles > 0);
  CHECK(sc["cycles"].get<uint64_t>() == cycles);
  CHECK(sc["end_ps"].get<double>() - sc["start_ps"].get<double>() == Approx(4000.0 * cycles));
  CHECK(run.rays.size() == 20);
  // The count does not depend on the quantum: 20 identical searches back to back.
  CHECK(cycles == 20 * (run.result.counters.latency_max) + 1);
}

TEST_CASE("throughput with ideal memory is within 2 percent of the unit bound", "[cycle]") {
  auto src = open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  const SceneAndBvh sb = load_trace_scene(src->header());
  const std::vector<TraceRay> rays = bench_rays(sb.scene, 24000, 3);
  HwConfig cfg;
  cfg.cores = 3;
  cfg.slots_per_core = 64;
  cfg.memory.ideal = true;
  cfg.memory.ideal_latency = 10;
  cfg.source = {1, 0, 0};
  cfg.box = {GENERATE(1u, 2u), 6, 1};
  cfg.triangle = {1, 15, GENERATE(1u, 3u)};
  const Run run = run_rays(rays, sb.scene, sb.bvh, ReplayOptions{}, cfg);
  const KindStats t = run.result.stats.total();
  REQUIRE(t.rays == rays.size());
  // Operations per ray from the functional counters: one box operation for
  // the root box and one per node fetch (both child boxes), one triangle
  // operation per triangle test. Bound, in rays per cycle:
  //   min( 1 / source_interval,
  //        cores * box.count / (box.issue_interval * box_ops_per_ray),
  //        cores * triangle.count / (triangle.issue_interval * triangle_ops_per_ray) )
  const double n = static_cast<double>(t.rays);
  const double box_per_ray = (n + t.traversal.node_visits) / n;
  const double tri_per_ray = t.traversal.triangle_tests / n;
  const double bound = std::min({1.0 / cfg.source.issue_interval,
                                 cfg.cores * cfg.box.count / (cfg.box.issue_interval * box_per_ray),
                                 cfg.cores * cfg.triangle.count / (cfg.triangle.issue_interval * tri_per_ray)});
  const double got = n / run.result.counters.cycles;
  INFO("box ops/ray " << box_per_ray << " triangle ops/ray " << tri_per_ray << " bound " << bound << " got " << got);
  CHECK(got <= bound * 1.0000001);
  CHECK(got >= 0.98 * bound);
}

TEST_CASE("the traversal controller: each step passes through it, its latency and issue interval by hand",
          "[cycle][controller]") {
  const ThreeFloors f;
  const uint32_t M = 3, Lb = 5, Lt = 11, La = 7, C = 10;
  TraceRay a = down_from(1, 1.0f);
  // Ray A as in the three-node case: root box, node 0, node 1, leaf [prim 0],
  // then its result. Each of those four steps' ends passes the controller.
  HwConfig cfg = one_slot(M, Lb, Lt, La);
  cfg.controller.count = 1;
  cfg.controller.latency = C;
  const Run run = run_rays({a}, f.scene, f.bvh, ReplayOptions{}, cfg);
  REQUIRE(run.rays.at(1).prim == 0);
  const uint64_t latency_a = Lb + (M + Lb) + (M + Lb) + (M + Lt);
  CHECK(run.rays.at(1).cycle == 1 + latency_a + 4 * C);
  CHECK(run.result.counters.controller.ops == 4);
  CHECK(run.result.counters.controller.wait_cycles == 0);
  CHECK(run.result.hw["units"]["controller"]["ops"] == 4);
  CHECK(run.result.hw["stalls"]["slot_cycles"]["controller_full"] == 0);

  // Without a controller (count 0, the default) nothing is added and nothing reported.
  cfg.controller.count = 0;
  const Run plain = run_rays({a}, f.scene, f.bvh, ReplayOptions{}, cfg);
  CHECK(plain.rays.at(1).cycle == 1 + latency_a);
  CHECK_FALSE(plain.result.hw["units"].contains("controller"));
}

TEST_CASE("the traversal controller's issue interval bounds a core's steps", "[cycle][controller]") {
  // A root leaf of one floor: each ray is the root box, the leaf and its result,
  // two controller passes. 32 slots keep many rays in flight, so the one
  // controller taking a step every I cycles is the bound: 2 I cycles a ray.
  const OneFloorLeaf leaf;
  const Scene& scene = leaf.scene;
  const Bvh& bvh = leaf.bvh;
  const uint32_t I = 6, rays = 60;
  HwConfig cfg = one_slot(1, 1, 1, 1);
  cfg.slots_per_core = 32;
  cfg.controller.count = 1;
  cfg.controller.issue_interval = I;
  std::vector<TraceRay> batch;
  for (uint32_t i = 0; i < rays; ++i) batch.push_back(down_from(i, 1.0f));
  const Run run = run_rays(batch, scene, bvh, ReplayOptions{}, cfg);
  const uint64_t cycles = run.result.counters.cycles;
  CHECK(run.result.counters.controller.ops == 2 * rays);
  CHECK(cycles >= 2 * I * (rays - 1));
  CHECK(cycles <= 2 * I * rays + 10);
  CHECK(run.result.counters.controller.wait_cycles > 0);
  // Two controllers halve it.
  cfg.controller.count = 2;
  const uint64_t two = run_rays(batch, scene, bvh, ReplayOptions{}, cfg).result.counters.cycles;
  CHECK(two >= I * (rays - 1));
  CHECK(two <= I * rays + 10);
}

TEST_CASE("the controller takes each kind of step with its own latency and issue interval, by hand",
          "[cycle][controller]") {
  // Ray A of the three-node case: its start, two node steps and a leaf pass
  // the controller; each with the latency of its kind.
  const ThreeFloors f;
  const uint32_t M = 3, Lb = 5, Lt = 11, La = 7, Ls = 4, Ln = 1, Ll = 9;
  HwConfig cfg = one_slot(M, Lb, Lt, La);
  cfg.controller.count = 1;
  cfg.controller.latency = 100;  // the default of the kinds not set: none here
  cfg.controller.by_step[ControllerConfig::Start] = {true, Ls, 1};
  cfg.controller.by_step[ControllerConfig::Node] = {true, Ln, 1};
  cfg.controller.by_step[ControllerConfig::Leaf] = {true, Ll, 1};
  const Run run = run_rays({down_from(1, 1.0f)}, f.scene, f.bvh, ReplayOptions{}, cfg);
  REQUIRE(run.rays.at(1).prim == 0);
  const uint64_t latency_a = Lb + (M + Lb) + (M + Lb) + (M + Lt);
  CHECK(run.rays.at(1).cycle == 1 + latency_a + Ls + 2 * Ln + Ll);
  CHECK(run.result.counters.controller.busy_cycles == 4);

  // Issue intervals: a root leaf of one floor, each ray a start and a leaf; with
  // 32 slots the one controller is the bound, Is + Il cycles a ray.
  const OneFloorLeaf leaf;
  const uint32_t Is = 2, Il = 5, rays = 60;
  HwConfig bound = one_slot(1, 1, 1, 1);
  bound.slots_per_core = 32;
  bound.controller.count = 1;
  bound.controller.by_step[ControllerConfig::Start] = {true, 0, Is};
  bound.controller.by_step[ControllerConfig::Leaf] = {true, 0, Il};
  std::vector<TraceRay> batch;
  for (uint32_t i = 0; i < rays; ++i) batch.push_back(down_from(i, 1.0f));
  const Run busy = run_rays(batch, leaf.scene, leaf.bvh, ReplayOptions{}, bound);
  const uint64_t cycles = busy.result.counters.cycles;
  CHECK(busy.result.counters.controller.busy_cycles == rays * (Is + Il));
  CHECK(cycles >= (Is + Il) * (rays - 1));
  CHECK(cycles <= (Is + Il) * rays + 10);
  const double util = busy.result.hw["units"]["controller"]["utilisation"].get<double>();
  CHECK(util == Approx(double(rays * (Is + Il)) / double(cycles)));
  CHECK(util > 0.9);
}

TEST_CASE("without the root box test a ray starts with the root node's fetch: the same hits, the work by hand",
          "[cycle][root-box]") {
  // 2,000 random bunny rays (the bench's), many missing the bunny. Without the
  // root test each ray saves its root box operation, and each of the M rays
  // that the root test would have ended fetches the root node instead and tests
  // its two children (both missed: they lie inside the root's box): box
  // operations -N + M, node visits +M, box tests -N + 2 M.
  const Scene scene = load_scene(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj");
  const Bvh bvh = build_bvh(scene);
  std::vector<TraceRay> rays = bench_rays(scene, 2000, 1);
  // The bench aims every ray into the bunny's box: turn every fourth around
  // (from outside the box, away from it: the root test ends it).
  for (size_t i = 0; i < rays.size(); i += 4)
    for (int a = 0; a < 3; ++a) rays[i].d[a] = -rays[i].d[a];
  HwConfig cfg = load_preset("small", "test");
  const Run with = run_rays(rays, scene, bvh, ReplayOptions{}, cfg);
  cfg.root_box_test = false;
  const Run without = run_rays(rays, scene, bvh, ReplayOptions{}, cfg);
  REQUIRE(with.rays.size() == rays.size());
  size_t same = 0;
  for (const auto& [id, f] : with.rays) same += without.rays.at(id).prim == f.prim;
  CHECK(same == rays.size());
  const auto traversal = [](const Run& r) { return r.result.stats.by_kind[static_cast<int>(RayKind::Primary)].traversal; };
  const TraversalCounters a = traversal(with), b = traversal(without);
  const uint64_t n = rays.size(), m = b.node_visits - a.node_visits;
  CHECK(m > 100);  // rays that miss the bunny's box (most of the 500 turned around)
  CHECK(b.box_tests == a.box_tests - n + 2 * m);
  CHECK(without.result.counters.box.ops == with.result.counters.box.ops - n + m);
  CHECK(without.result.hw["units"]["box"]["ops"] == without.result.counters.box.ops);
}

TEST_CASE("per-triangle fetch: each triangle read after the one before has its result, by hand",
          "[cycle][triangle-fetch]") {
  // The root leaf of three floors, as above, its triangles read one by one.
  const ThreeFloorsLeaf leaf;
  const Scene& scene = leaf.scene;
  const Bvh& bvh = leaf.bvh;
  const uint32_t M = 4, Lb = 2, Lt = 9, F = 3;
  HwConfig cfg = one_slot(M, Lb, Lt, 1);
  cfg.triangle.issue_interval = 3;
  cfg.source.issue_interval = 5;  // the ray is dispatched at cycle 5
  cfg.per_triangle_fetch = true;
  cfg.triangle_fetch_cycles = F;
  const Run run = run_rays({down_from(7, 1.0f)}, scene, bvh, ReplayOptions{}, cfg);
  REQUIRE(run.rays.at(7).prim == 0);
  // Root box; read triangle 0 (M) and test it at R0; triangle 1's read starts
  // F after that result (Lt), its test when it arrives (M); the same for
  // triangle 2; its result Lt later.
  const uint64_t r0 = 5 + Lb + M;
  CHECK(run.rays.at(7).cycle == r0 + 2 * (Lt + F + M) + Lt);
  CHECK(run.result.counters.triangle.ops == 3);
  CHECK(run.result.counters.memory_wait_cycles == 3 * M);
  CHECK(run.result.counters.leaf_fetches == 1);  // one leaf visited, read in three

  // With a traversal controller the leaf is one step, as when it is read
  // whole: the root box's end and the leaf's end pass it (C each); the
  // triangles' reads do not.
  const uint32_t C = 6;
  cfg.controller.count = 1;
  cfg.controller.latency = C;
  const Run controlled = run_rays({down_from(7, 1.0f)}, scene, bvh, ReplayOptions{}, cfg);
  CHECK(controlled.result.counters.controller.ops == 2);
  CHECK(controlled.rays.at(7).cycle == r0 + C + 2 * (Lt + F + M) + Lt + C);
  // Read whole, the leaf's tests issue back to back.
  cfg.per_triangle_fetch = false;
  const Run whole = run_rays({down_from(7, 1.0f)}, scene, bvh, ReplayOptions{}, cfg);
  CHECK(whole.result.counters.controller.ops == 2);
  CHECK(whole.rays.at(7).cycle == r0 + C + 2 * 3 + Lt + C);
}

TEST_CASE("per-triangle fetch gives the bundled trace's hits, in more cycles", "[cycle][triangle-fetch]") {
  auto src = open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  const SceneAndBvh sb = load_trace_scene(src->header());
  std::vector<TraceRay> rays;
  TraceRay tr;
  while (src->next(tr)) rays.push_back(tr);
  const ReplayOptions opt = validity_bit_options();
  HwConfig cfg = load_preset("small", "test");
  cfg.controller.count = 1;  // every step counted
  const Run leaf = run_rays(rays, sb.scene, sb.bvh, opt, cfg);
  cfg.per_triangle_fetch = true;
  const Run each = run_rays(rays, sb.scene, sb.bvh, opt, cfg);
  REQUIRE(each.rays.size() == rays.size());
  size_t differ = 0;
  for (const auto& [id, f] : leaf.rays) differ += each.rays.at(id).prim != f.prim;
  CHECK(differ == 0);
  CHECK(each.result.counters.triangle.ops == leaf.result.counters.triangle.ops);
  CHECK(each.result.counters.leaf_fetches == leaf.result.counters.leaf_fetches);
  // The same steps through the controller; each triangle waits for the one before.
  CHECK(each.result.counters.controller.ops == leaf.result.counters.controller.ops);
  CHECK(each.result.counters.cycles > leaf.result.counters.cycles);
}

TEST_CASE("without pop culling a popped subtree beyond the hit is visited all the same, by hand", "[cycle][pop-culling]") {
  const ThreeFloors f;
  const uint32_t M = 3, Lb = 5, Lt = 11, La = 7;
  const ReplayOptions opt = validity_bit_options();
  // Ray A of the first test: root box, node 0, node 1, leaf [prim 0], a hit
  // at t = 1. Leaves [prim 1] and [prim 2] were pushed beyond it: culled when
  // popped; without culling each is fetched and its triangle tested (a hit
  // farther than t = 1, not taken).
  HwConfig cfg = one_slot(M, Lb, Lt, La);
  const Run culled = run_rays({down_from(1, 1.0f)}, f.scene, f.bvh, opt, cfg);
  cfg.pop_culling = false;
  const Run visited = run_rays({down_from(1, 1.0f)}, f.scene, f.bvh, opt, cfg);
  REQUIRE(culled.rays.at(1).prim == 0);
  CHECK(visited.rays.at(1).prim == 0);
  CHECK(culled.rays.at(1).cycle == 1 + Lb + 2 * (M + Lb) + (M + Lt));
  CHECK(visited.rays.at(1).cycle == culled.rays.at(1).cycle + 2 * (M + Lt));
  CHECK(visited.result.counters.triangle.ops == culled.result.counters.triangle.ops + 2);
  CHECK(visited.result.counters.leaf_fetches == culled.result.counters.leaf_fetches + 2);
}

TEST_CASE("a node whose children are both low-precision goes to the low-precision box pool, by hand",
          "[cycle][box-low]") {
  ThreeFloors f;
  const uint32_t M = 3, Lb = 5, Lt = 11, La = 7, Llow = 2;
  const ReplayOptions opt = validity_bit_options();
  HwConfig cfg = one_slot(M, Lb, Lt, La);
  cfg.box_low = {1, Llow, 1};
  // Ray A of the first test: root box, node 0, node 1, leaf [prim 0]. Node 0
  // marked for the low-precision pool: its test takes Llow instead of Lb.
  f.bvh.low_precision_node.assign(f.bvh.nodes.size(), 0);
  f.bvh.low_precision_node[0] = 1;
  const Run run = run_rays({down_from(1, 1.0f)}, f.scene, f.bvh, opt, cfg);
  REQUIRE(run.rays.at(1).prim == 0);
  CHECK(run.rays.at(1).cycle == 1 + Lb + (M + Llow) + (M + Lb) + (M + Lt));
  CHECK(run.result.counters.box_low.ops == 1);
  CHECK(run.result.counters.box.ops == 2);  // the root box and node 1
  CHECK(run.result.hw["units"]["box_low"]["ops"] == 1);
  // The same through the units' interfaces (a replaced triangle tester, here
  // one of full precision): node 0 still goes to the low-precision pool.
  CycleRunOptions options;
  options.track_parents = false;
  options.units.triangle_tester = reduced_precision_triangle_tester(23, TesterKind::ThreeHalfPlane);
  uint64_t finish = 0;
  const CycleRunResult ported = run_cycle_replay(
      feed_of({down_from(1, 1.0f)}), f.scene, f.bvh, opt, cfg,
      [&](const TraceRay&, const RayOutcome&, uint64_t cycle, uint64_t) { finish = cycle; }, options);
  CHECK(finish == run.rays.at(1).cycle);
  CHECK(ported.counters.box_low.ops == 1);
  // Without a pool the marks change nothing: node 0 goes to the box unit.
  cfg.box_low.count = 0;
  const Run no_pool = run_rays({down_from(1, 1.0f)}, f.scene, f.bvh, opt, cfg);
  CHECK(no_pool.rays.at(1).cycle == 1 + Lb + 2 * (M + Lb) + (M + Lt));
  CHECK(no_pool.result.counters.box.ops == 3);
  CHECK_FALSE(no_pool.result.hw["units"].contains("box_low"));
}

TEST_CASE("a 4-wide node is one 128-byte fetch and one box operation for all its children, by hand",
          "[cycle][wide]") {
  // The three floors collapsed 4 wide: node 0 = {leaf [prim 0], leaf [prim 1],
  // leaf [prim 2]} (node 1 opened in place: slots in the binary walk's order).
  ThreeFloors f;
  collapse_bvh(f.bvh, 4);
  REQUIRE(f.bvh.nodes4.size() == 1);
  REQUIRE(f.bvh.nodes4[0].children == 3);
  const BvhAddressMap map(f.bvh, 4096);
  CHECK(map.node_bytes == 128);
  CHECK(map.node(1) == 4096 + 128);
  CHECK(map.triangle(0) == 4096 + 128);  // one wide node before the triangles
  const uint32_t M = 3, Lb = 5, Lt = 11, La = 7;
  TraceRay a = down_from(1, 1.0f);
  TraceRay b = down_from(2, 1e-7f);  // as in the three-node case: prim 0 rejected, prim 1 accepted
  b.parent = 1;
  b.parent_prim = 0;
  b.kind = RayKind::Reflect;
  b.sign = 1;
  HwConfig cfg = one_slot(M, Lb, Lt, La);
  cfg.source.dependencies = false;
  const Run run = run_rays({a, b}, f.scene, f.bvh, validity_bit_options(), cfg);
  REQUIRE(run.rays.at(1).prim == 0);
  REQUIRE(run.rays.at(2).prim == 1);
  const uint64_t latency_a = Lb + (M + Lb) + (M + Lt);  // root box, node 0 (three boxes), leaf [prim 0]
  const uint64_t latency_b = Lb + (M + Lb) + (M + Lt + La) + (M + Lt + La);
  CHECK(run.rays.at(1).cycle == 1 + latency_a);
  CHECK(run.rays.at(2).cycle == 1 + latency_a + latency_b);
  const HwCounters& c = run.result.counters;
  CHECK(c.box.ops == 4);  // one a node, where the binary tree took two nodes
  CHECK(c.triangle.ops == 3);
  CHECK(c.memory_wait_cycles == 5 * M);
}

TEST_CASE("a triangle tester shared by two cores takes both cores' tests in one reservation table, by hand",
          "[cycle][share]") {
  // A root leaf of three floors; two cores of one slot. Ray 1 is dispatched at
  // cycle 1 to core 0, ray 2 at cycle 2 to core 1 (least loaded); each meets
  // all three floors, so each takes three triangle tests, all ready when its
  // leaf arrives: R1 = 1 + Lb + M and R2 = R1 + 1.
  const ThreeFloorsLeaf leaf;
  const uint32_t M = 4, Lb = 2, Lt = 9, interval = 3;
  HwConfig cfg = one_slot(M, Lb, Lt, 1);
  cfg.cores = 2;
  cfg.triangle.issue_interval = interval;
  cfg.source.dependencies = false;
  const uint64_t r1 = 1 + Lb + M;
  SECTION("each core its own tester: the two rays' tests overlap") {
    const Run run = run_rays({down_from(1, 1.0f), down_from(2, 1.0f)}, leaf.scene, leaf.bvh, ReplayOptions{}, cfg);
    CHECK(run.rays.at(1).cycle == r1 + 2 * interval + Lt);
    CHECK(run.rays.at(2).cycle == r1 + 1 + 2 * interval + Lt);
    CHECK(run.result.counters.triangle.ops == 6);
  }
  SECTION("one tester for both cores: ray 2's tests take the issue cycles after ray 1's") {
    cfg.triangle.share = 2;
    const Run run = run_rays({down_from(1, 1.0f), down_from(2, 1.0f)}, leaf.scene, leaf.bvh, ReplayOptions{}, cfg);
    REQUIRE(run.rays.at(2).prim == 0);
    // Ray 1 holds the pipeline at R1, R1 + 3, R1 + 6; ray 2 (ready at R1 + 1)
    // issues at R1 + 9, R1 + 12, R1 + 15.
    CHECK(run.rays.at(1).cycle == r1 + 2 * interval + Lt);
    CHECK(run.rays.at(2).cycle == r1 + 5 * interval + Lt);
    CHECK(run.result.counters.triangle.ops == 6);  // counted once, not once per core
    CHECK(run.result.counters.triangle.wait_cycles == 2 * (interval - 1) + (3 * interval - 1) + 2 * (interval - 1));
  }
}

TEST_CASE("throughput with units shared by groups of cores is within 2 percent of the shared units' bound",
          "[cycle][share]") {
  auto src = open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  const SceneAndBvh sb = load_trace_scene(src->header());
  const std::vector<TraceRay> rays = bench_rays(sb.scene, 24000, 5);
  HwConfig cfg;
  cfg.cores = 4;
  cfg.slots_per_core = 64;
  cfg.memory.ideal = true;
  cfg.memory.ideal_latency = 10;
  cfg.source = {1, 0, 0};
  cfg.box = {8, 6, 1};  // enough box units that the triangle testers bound the throughput
  cfg.triangle = {1, 15, 4};
  cfg.triangle.share = GENERATE(1u, 2u, 4u);  // 4, 2 and 1 testers
  const Run run = run_rays(rays, sb.scene, sb.bvh, ReplayOptions{}, cfg);
  const KindStats t = run.result.stats.total();
  REQUIRE(t.rays == rays.size());
  const double n = static_cast<double>(t.rays);
  const double tri_per_ray = t.traversal.triangle_tests / n;
  const uint32_t testers = unit_groups(cfg.triangle, cfg.cores);
  const double bound = std::min({1.0 / cfg.source.issue_interval,
                                 testers * cfg.triangle.count / (cfg.triangle.issue_interval * tri_per_ray)});
  const double got = n / run.result.counters.cycles;
  INFO("share " << cfg.triangle.share << " triangle ops/ray " << tri_per_ray << " bound " << bound << " got " << got);
  CHECK(got <= bound * 1.0000001);
  CHECK(got >= 0.98 * bound);
}
