// Loosely timed memory gives the cycles of approximately timed memory: the
// bundled trace and a 93,000-ray path trace on both presets, with DRAM
// latencies, bandwidths and request limits from idle to saturated, ray by ray.
// The L2's requests reach a loosely timed target in time order, each annotated
// with its own cycle (a recording target of the test's own, against the same
// target approximately timed).
#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

#include "accelerator_harness.h"
#include "hw/cycle_replay.h"
#include "recording_memory.h"
#include "trace_in_memory.h"
#include "../system/run_vbsim.h"
#include "../unit/three_floors.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

using Trace = TraceInMemory;

struct Timed {
  uint64_t cycles = 0;
  std::vector<uint64_t> finish;  ///< by trace position
  nlohmann::json memory;
};

Timed run_style(const Trace& t, HwConfig cfg, TlmStyle style) {
  cfg.memory.tlm = style;
  Timed out;
  out.finish.resize(t.rays.size());
  CycleRunOptions options;
  options.ray_times = [&](const RayTimes& rt) { out.finish[rt.trace_index] = rt.finished; };
  const CycleRunResult r = run_cycle_replay(feed_of(t.rays), t.sb.scene, t.sb.bvh, ReplayOptions{}, cfg, {}, options);
  out.cycles = r.counters.cycles;
  out.memory = r.hw["memory"]["port"];
  return out;
}

/// LT and AT on `t` with `cfg`: the same cycles, ray by ray, and the same memory statistics.
void check_styles(const Trace& t, const HwConfig& cfg) {
  const Timed lt = run_style(t, cfg, TlmStyle::LooselyTimed);
  const Timed at = run_style(t, cfg, TlmStyle::ApproximatelyTimed);
  CHECK(lt.cycles == at.cycles);
  size_t differ = 0;
  for (size_t i = 0; i < lt.finish.size(); ++i) differ += lt.finish[i] != at.finish[i];
  CHECK(differ == 0);
  CHECK(lt.memory["dram"] == at.memory["dram"]);
  CHECK(lt.memory["stall_cycles"] == at.memory["stall_cycles"]);
  CHECK(lt.memory["l2"] == at.memory["l2"]);
}

}  // namespace

TEST_CASE("loosely and approximately timed DRAM give the same cycles on the bundled trace, idle to saturated",
          "[module][tlm][styles]") {
  const Trace t = read_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  for (const char* preset : {"small", "large"})
    for (const uint32_t latency : {40u, 150u, 600u})
      for (const double bytes_per_cycle : {2.0, 16.0, 4096.0})
        for (const uint32_t outstanding : {1u, 4u, 32u}) {
          INFO(preset << ": DRAM latency " << latency << ", " << bytes_per_cycle << " bytes/cycle, "
                      << outstanding << " outstanding");
          HwConfig cfg = load_preset(preset, "test");
          cfg.memory.dram_latency = latency;
          cfg.memory.dram_bytes_per_cycle = bytes_per_cycle;
          cfg.memory.dram_max_outstanding = outstanding;
          check_styles(t, cfg);
        }
}

TEST_CASE("L2 lookups in time order: the same hits as the functional replay, the same cycles in both styles",
          "[module][tlm][styles]") {
  // memory.l2_lookups_in_time_order: an L1 miss that waits for an MSHR is looked
  // up in the L2 at the cycle it leaves (a memory step), not when it is found.
  const Trace t = read_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  FunctionalReplayer functional(t.sb.scene, t.sb.bvh, ReplayOptions{});
  std::vector<int32_t> want;
  for (const TraceRay& r : t.rays) want.push_back(functional.replay(r).hit.prim);
  for (const char* preset : {"small", "large"}) {
    INFO(preset);
    HwConfig cfg = load_preset(preset, "test");
    const Timed ahead = run_style(t, cfg, TlmStyle::LooselyTimed);
    cfg.memory.l2_lookups_in_time_order = true;
    check_styles(t, cfg);
    std::vector<int32_t> got(t.rays.size(), -2);
    CycleRunOptions options;
    const CycleRunResult r = run_cycle_replay(
        feed_of(t.rays), t.sb.scene, t.sb.bvh, ReplayOptions{}, cfg,
        [&](const TraceRay&, const RayOutcome& out, uint64_t, uint64_t index) { got[index] = out.hit.prim; }, options);
    CHECK(got == want);
    // Every L1 miss that waited for an MSHR went through the memory step: the
    // L1s' MSHR waits are there, and the cycles moved.
    CHECK(r.hw["memory"]["port"]["l1"]["mshr_stall_cycles"].get<uint64_t>() > 0);
    CHECK(r.counters.cycles != ahead.cycles);
  }
}

TEST_CASE("the issue's case: a wide channel shows no bandwidth stalls in either style", "[module][tlm][styles]") {
  // {"memory": {"tlm": "lt", "dram_latency": 120, "dram_max_outstanding": 32,
  // "dram_bytes_per_cycle": 4096}}: a line moves in 1/64 cycle, so requests
  // that arrive in time order never wait for the channel.
  const Trace t = read_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  HwConfig cfg = load_preset("small", "test");
  cfg.memory.dram_latency = 120;
  cfg.memory.dram_max_outstanding = 32;
  cfg.memory.dram_bytes_per_cycle = 4096;
  const Timed lt = run_style(t, cfg, TlmStyle::LooselyTimed);
  CHECK(lt.memory["stall_cycles"]["dram_bandwidth"] == 0);
  CHECK(lt.cycles == run_style(t, cfg, TlmStyle::ApproximatelyTimed).cycles);
}

TEST_CASE("loosely and approximately timed DRAM give the same cycles on a 93,000-ray path trace",
          "[module][tlm][styles]") {
  const auto dir = vbsim::test::scratch_dir("styles_paths");
  REQUIRE(vbsim::test::run_vbsim("gen paths --rays 20000 --seed 5 -q -o " + dir.string()).exit_code == 0);
  const Trace t = read_trace((dir / "paths.jsonl").string());
  REQUIRE(t.rays.size() > 90000);
  for (const char* preset : {"small", "large"})
    for (const uint32_t outstanding : {8u, 64u}) {
      INFO(preset << ", " << outstanding << " outstanding");
      HwConfig cfg = load_preset(preset, "test");
      cfg.memory.dram_max_outstanding = outstanding;
      cfg.memory.dram_bytes_per_cycle = 8;
      check_styles(t, cfg);
    }
  std::filesystem::remove_all(dir);
}

TEST_CASE("a loosely timed target of one's own sees the L2's requests in time order, as approximately timed",
          "[module][tlm][styles]") {
  const Trace t = read_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  std::vector<uint64_t> arrivals[2], finish[2];
  for (const TlmStyle style : {TlmStyle::LooselyTimed, TlmStyle::ApproximatelyTimed}) {
    const int k = style == TlmStyle::ApproximatelyTimed;
    HwConfig cfg = load_preset("small", "test");
    cfg.memory.tlm = style;
    AcceleratorUnits units;
    units.external_memory = true;
    AcceleratorHarness h(t.sb.scene, t.sb.bvh, cfg, ReplayOptions{}, units,
                         [&cfg](Accelerator& acc) -> std::unique_ptr<sc_core::sc_module> {
                           auto m = std::make_unique<RecordingMemory>("recording_memory",
                                                                      CycleClock(cfg.clock_mhz).period(), 90);
                           acc.memory_socket().bind(m->socket);
                           return m;
                         });
    std::vector<TraceRay> rays = t.rays;
    for (TraceRay& r : rays) r.parent = -1;  // the harness feeds rays as unrelated queries
    h.run(rays);
    arrivals[k] = h.attached<RecordingMemory>()->arrivals;
    for (const auto& [id, fin] : h.finished) finish[k].push_back(fin.cycle);
  }
  REQUIRE(arrivals[0].size() > 100);
  CHECK(std::is_sorted(arrivals[0].begin(), arrivals[0].end()));  // time order, each at its own cycle
  CHECK(arrivals[0] == arrivals[1]);
  CHECK(finish[0] == finish[1]);
}

TEST_CASE("misses not merged: the same hits, more DRAM reads, and the same cycles in both styles",
          "[module][tlm][styles][merging]") {
  // Without merging, every request for a line in flight is a miss of its own
  // whose answer may be pending (kPendingCycle) behind either style: each
  // pending miss is answered by its own fill, in the order asked for.
  const Trace t = read_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  FunctionalReplayer functional(t.sb.scene, t.sb.bvh, ReplayOptions{});
  std::vector<int32_t> want;
  for (const TraceRay& r : t.rays) want.push_back(functional.replay(r).hit.prim);
  for (const char* preset : {"small", "large"})
    for (const bool l2_merges : {true, false})
      for (const bool in_time_order : {false, true}) {
        INFO(preset << ", L2 merges " << l2_merges << ", L2 lookups in time order " << in_time_order);
        HwConfig cfg = load_preset(preset, "test");
        cfg.memory.l2_lookups_in_time_order = in_time_order;
        const Timed merging = run_style(t, cfg, TlmStyle::LooselyTimed);
        cfg.memory.l1.merge_misses = false;
        cfg.memory.l2.merge_misses = l2_merges;
        check_styles(t, cfg);
        const Timed apart = run_style(t, cfg, TlmStyle::LooselyTimed);
        CHECK(apart.memory["l1"]["merges"] == 0);
        CHECK(apart.memory["l1"]["misses"].get<uint64_t>() > merging.memory["l1"]["misses"].get<uint64_t>());
        if (!l2_merges) {
          CHECK(apart.memory["l2"]["merges"] == 0);
          CHECK(apart.memory["dram"]["reads"].get<uint64_t>() > merging.memory["dram"]["reads"].get<uint64_t>());
        }
        std::vector<int32_t> got(t.rays.size(), -2);
        run_cycle_replay(feed_of(t.rays), t.sb.scene, t.sb.bvh, ReplayOptions{}, cfg,
                         [&](const TraceRay&, const RayOutcome& out, uint64_t, uint64_t index) {
                           got[index] = out.hit.prim;
                         },
                         CycleRunOptions{});
        CHECK(got == want);
      }
}
