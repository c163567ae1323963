// Child rays wait for their parents whatever the trace order, the emission
// window and the shading latency: the bundled trace and a 93,000-ray path trace
// reordered breadth-first (every camera ray, then every first bounce, ...; ids
// renumbered ascending, a valid trace), windows 0 to 4096, latencies 0 to
// 100,000, both presets and ideal memory, every run's ray log checked ray by
// ray: each ray once; a child ready exactly when it entered the buffer or when
// its parent's result plus the shading latency came, whichever is later; no ray
// read further than the window beyond the oldest unfinished one.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <unordered_map>

#include "hw/cycle_replay.h"
#include "trace_in_memory.h"
#include "../system/run_vbsim.h"
#include "../unit/three_floors.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

using Trace = TraceInMemory;

/// `rays` in breadth-first order: by generation (a camera ray 0, its children
/// 1, ...), trace order within one; ids renumbered 0, 1, 2, ... in the new
/// order, parents renamed with them.
std::vector<TraceRay> breadth_first(const std::vector<TraceRay>& rays) {
  std::unordered_map<int64_t, int> depth;
  std::vector<std::pair<int, size_t>> order;
  for (size_t i = 0; i < rays.size(); ++i) {
    const auto p = depth.find(rays[i].parent);
    const int d = rays[i].parent >= 0 && p != depth.end() ? p->second + 1 : 0;
    depth[rays[i].id] = d;
    order.push_back({d, i});
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::unordered_map<int64_t, int64_t> renamed;
  std::vector<TraceRay> out;
  for (const auto& [d, i] : order) {
    TraceRay r = rays[i];
    renamed[r.id] = static_cast<int64_t>(out.size());
    r.id = static_cast<int64_t>(out.size());
    if (r.parent >= 0) r.parent = renamed.at(r.parent);  // a parent is a generation earlier: renamed already
    out.push_back(r);
  }
  return out;
}

struct Run {
  std::vector<RayTimes> times;  ///< by trace position
  CycleRunResult result;
};

Run run(const Trace& t, const std::vector<TraceRay>& rays, const HwConfig& cfg) {
  Run out;
  out.times.resize(rays.size());
  std::vector<bool> seen(rays.size(), false);
  CycleRunOptions options;
  options.ray_times = [&](const RayTimes& rt) {
    REQUIRE(rt.trace_index < rays.size());
    REQUIRE_FALSE(seen[rt.trace_index]);  // each ray finishes once
    seen[rt.trace_index] = true;
    out.times[rt.trace_index] = rt;
  };
  out.result = run_cycle_replay(feed_of(rays), t.sb.scene, t.sb.bvh, ReplayOptions{}, cfg, {}, options);
  REQUIRE(std::count(seen.begin(), seen.end(), true) == static_cast<long>(rays.size()));
  return out;
}

/// What the ray log of one run broke, counted.
struct LogCheck {
  size_t children = 0, waited = 0;  ///< child rays; of which ready after they entered
  size_t early = 0;     ///< ready before the parent's result plus the latency
  size_t late = 0;      ///< ready later than needed
  size_t disorder = 0;  ///< not entered <= ready <= emitted < started < finished
  size_t beyond = 0;    ///< entered while a ray more than the window before it had not finished
};

LogCheck check_log(const std::vector<TraceRay>& rays, const std::vector<RayTimes>& times, uint64_t latency,
                   uint32_t window) {
  LogCheck c;
  std::unordered_map<int64_t, size_t> pos;
  for (size_t i = 0; i < rays.size(); ++i) {
    const RayTimes& t = times[i];
    c.disorder += !(t.id == rays[i].id && t.entered <= t.ready && t.ready <= t.emitted && t.emitted < t.started &&
                    t.started < t.finished);
    pos[rays[i].id] = i;
    if (rays[i].parent < 0) {
      c.late += t.ready != t.entered;
      continue;
    }
    ++c.children;
    const uint64_t due = times[pos.at(rays[i].parent)].finished + latency;
    c.early += t.ready < due;
    c.late += t.ready != std::max(due, t.entered);
    c.waited += t.ready > t.entered;
  }
  // The window: when ray i entered, every ray before i - window had finished
  // (by then or in that cycle: a ray finishing at the cycle frees its place).
  uint64_t oldest_unfinished_finish = 0;  // the latest finish among rays [0, i - window)
  for (size_t i = 0; i < rays.size(); ++i) {
    if (i > window) oldest_unfinished_finish = std::max(oldest_unfinished_finish, times[i - window - 1].finished);
    c.beyond += times[i].entered < oldest_unfinished_finish;
  }
  return c;
}

HwConfig configured(const std::string& preset, bool ideal, uint32_t window, uint32_t latency) {
  HwConfig cfg = load_preset(preset, "test");
  cfg.memory.ideal = ideal;
  cfg.source.window = window;
  cfg.shader.latency_cycles = latency;
  return cfg;
}

std::string bundled() { return std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl"; }

void check_run(const Trace& t, const std::vector<TraceRay>& rays, const HwConfig& cfg) {
  const Run r = run(t, rays, cfg);
  const LogCheck c = check_log(rays, r.times, cfg.shader.latency_cycles, cfg.source.window);
  CHECK(c.children > 0);
  CHECK(c.early == 0);
  CHECK(c.late == 0);
  CHECK(c.disorder == 0);
  CHECK(c.beyond == 0);
  CHECK(r.result.hw["emission"]["parents_not_found"] == 0);
  // Counted by the source: entered before the result was shaded (ready later,
  // or in the same cycle from a later event).
  CHECK(r.result.hw["emission"]["children_waited"] >= c.waited);
  CHECK(r.result.hw["emission"]["children_waited"] <= c.children);
}

}  // namespace

TEST_CASE("breadth-first and depth-first traces: children wait for their parents at every window and latency",
          "[module][deps][order]") {
  const Trace t = read_trace(bundled());
  const std::vector<TraceRay> breadth = breadth_first(t.rays);
  REQUIRE(breadth.size() == t.rays.size());
  const std::vector<TraceRay> first300(breadth.begin(), breadth.begin() + 300);
  for (const auto& [name, rays] : {std::pair<const char*, const std::vector<TraceRay>*>{"depth-first", &t.rays},
                                   {"breadth-first", &breadth},
                                   {"breadth-first, first 300", &first300}})
    for (const char* preset : {"small", "large"})
      for (const bool ideal : {true, false})
        for (const uint32_t window : {1u, 2u, 64u, 128u, 256u, 4096u})
          for (const uint32_t latency : {0u, 5000u, 100000u}) {
            INFO(name << ", " << preset << (ideal ? " ideal" : " hierarchy") << ", window " << window
                      << ", latency " << latency);
            check_run(t, *rays, configured(preset, ideal, window, latency));
          }
}

TEST_CASE("window 0 emits one ray at a time, window 1 keeps the oldest unfinished ray and one more",
          "[module][deps][order]") {
  const Trace t = read_trace(bundled());
  const std::vector<TraceRay> rays(t.rays.begin(), t.rays.begin() + 60);
  for (const uint32_t window : {0u, 1u}) {
    INFO("window " << window);
    HwConfig cfg = configured("small", true, window, 0);
    cfg.source.dependencies = false;  // only the window holds rays back
    const Run r = run(t, rays, cfg);
    // At most window + 1 rays read and unfinished at once: ray i enters once
    // ray i - window - 1 has finished.
    size_t overlapping = 0;  // rays started before the previous one finished
    for (size_t i = 1; i < rays.size(); ++i) {
      INFO("ray " << i);
      if (i > window) CHECK(r.times[i].entered >= r.times[i - window - 1].finished);
      overlapping += r.times[i].started < r.times[i - 1].finished;
    }
    if (window == 0) CHECK(overlapping == 0);  // one ray at a time
    else CHECK(overlapping > rays.size() / 2);  // two in flight
  }
}

TEST_CASE("the false deadlock and the early children of a breadth-first trace are gone", "[module][deps][order]") {
  const Trace t = read_trace(bundled());
  const std::vector<TraceRay> breadth = breadth_first(t.rays);
  // Window 128, latency 5000, the first 300 rays, ideal memory: the ring place
  // of a finished parent was reused while its children waited for the shader.
  const std::vector<TraceRay> first300(breadth.begin(), breadth.begin() + 300);
  const Run a = run(t, first300, configured("small", true, 128, 5000));
  const LogCheck ca = check_log(first300, a.times, 5000, 128);
  CHECK(ca.children > 60);
  CHECK(ca.early + ca.late == 0);
  // Window 64, latency 20000 on the whole trace: every child waits 20000 cycles
  // after its parent, so the run is longer than with latency 200.
  const Run b = run(t, breadth, configured("small", true, 64, 20000));
  const Run c = run(t, breadth, configured("small", true, 64, 200));
  const LogCheck cb = check_log(breadth, b.times, 20000, 64);
  CHECK(cb.children == 808);
  CHECK(cb.early == 0);
  CHECK(cb.late == 0);
  CHECK(b.result.counters.cycles > c.result.counters.cycles + 20000);
}

TEST_CASE("two paths, window 1, latency 100000: each child starts after its parent's result and the shader",
          "[module][deps][order]") {
  const ThreeFloors f;
  // Two camera rays, then a child of each: with window 1 the children enter
  // after the first camera ray finished, long before the shader is done.
  std::vector<TraceRay> rays = {down_from(1, 1.0f), down_from(2, 1.0f), down_from(3, 1.0f), down_from(4, 1.0f)};
  for (const int k : {2, 3}) {
    rays[k].parent = k - 1;
    rays[k].parent_prim = 0;
    rays[k].kind = RayKind::Reflect;
    rays[k].sign = 0;
  }
  HwConfig cfg = one_slot(3, 5, 11, 7);
  cfg.source.window = 1;
  cfg.shader.latency_cycles = 100000;
  Run r;
  r.times.resize(rays.size());
  CycleRunOptions options;
  options.ray_times = [&](const RayTimes& t) { r.times[t.trace_index] = t; };
  r.result = run_cycle_replay(feed_of(rays), f.scene, f.bvh, ReplayOptions{}, cfg, {}, options);
  // Each search takes 35 cycles (dependency_test.cpp): ray 1 done 36, ray 2 71.
  CHECK(r.times[0].finished == 36);
  CHECK(r.times[1].finished == 71);
  CHECK(r.times[2].ready == 36 + 100000);
  CHECK(r.times[3].ready == 71 + 100000);
  CHECK(r.times[3].started > r.times[3].ready);
}

TEST_CASE("a 93,000-ray path trace in breadth-first order: every child waits for its parent far behind the window",
          "[module][deps][order]") {
  const auto dir = vbsim::test::scratch_dir("order_paths");
  const auto gen = vbsim::test::run_vbsim("gen paths --rays 20000 --seed 3 -q -o " + dir.string());
  REQUIRE(gen.exit_code == 0);
  const Trace t = read_trace((dir / "paths.jsonl").string());
  const std::vector<TraceRay> breadth = breadth_first(t.rays);
  REQUIRE(breadth.size() > 90000);
  for (const char* preset : {"small", "large"}) {
    INFO(preset);
    const HwConfig cfg = configured(preset, true, 4096, 200);
    const Run r = run(t, breadth, cfg);
    const LogCheck c = check_log(breadth, r.times, 200, 4096);
    CHECK(c.children > 70000);
    CHECK(c.early == 0);
    CHECK(c.late == 0);
    CHECK(c.beyond == 0);
    CHECK(r.result.hw["emission"]["parents_not_found"] == 0);
  }
  std::filesystem::remove_all(dir);
}
