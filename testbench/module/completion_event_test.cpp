// The accelerator's completion signal (Accelerator::completion_event and the
// completion callback): notified exactly once, at the SystemC time of the last
// ray's finish (the run's cycles x the clock period, and the latest finish
// cycle the result sink reported), with loosely and approximately timed
// memory, an ideal memory, an approximately timed target of the user's own and
// quanta from 1 to 4096 cycles; the cycles are those of a plain run of the same
// configuration; a stopped run never notifies it. (The stop_at_completion option calls sc_stop(), which a Catch test must
// not: testbench/examples/clocked_design.cpp and its system test cover it.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <vector>

#include <systemc>

#include "accelerator_harness.h"
#include "banked_memory.h"
#include "hw/cycle_replay.h"
#include "trace_in_memory.h"
#include "../unit/three_floors.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

struct Moment {
  sc_core::sc_time time;
  uint64_t delta;
};

/// A module of the user's design that waits on the completion event, and
/// (with `memory`) the user's approximately timed memory target behind the L2.
class CompletionWatcher final : public sc_core::sc_module {
 public:
  std::vector<Moment> seen;

  CompletionWatcher(sc_core::sc_module_name name, Accelerator& acc, const BankedMemoryConfig* memory = nullptr)
      : sc_core::sc_module(name), completion_(acc.completion_event()) {
    SC_THREAD(watch);
    if (memory) {
      memory_ = std::make_unique<BankedMemory>("memory", *memory, CycleClock(acc.config().clock_mhz).period());
      acc.memory_socket().bind(memory_->socket);
    }
  }

 private:
  SC_HAS_PROCESS(CompletionWatcher);
  void watch() {
    for (;;) {
      wait(completion_);
      seen.push_back({sc_core::sc_time_stamp(), sc_core::sc_delta_count()});
    }
  }
  const sc_core::sc_event& completion_;
  std::unique_ptr<BankedMemory> memory_;
};

struct Callback {
  int calls = 0;
  uint64_t cycles = 0;
  Moment at;
};

/// Runs `t` on `cfg` with a watcher and a callback; checks the completion
/// signal against the run's cycles; returns the cycles.
uint64_t check_completion(const TraceInMemory& t, const HwConfig& cfg, const BankedMemoryConfig* memory = nullptr) {
  Callback cb;
  AcceleratorUnits units;
  units.external_memory = memory != nullptr;
  AcceleratorHarness h(t.sb.scene, t.sb.bvh, cfg, ReplayOptions{}, units, [&cb, memory](Accelerator& acc) {
    acc.set_completion_callback([&cb](uint64_t cycles) {
      ++cb.calls;
      cb.cycles = cycles;
      cb.at = {sc_core::sc_time_stamp(), sc_core::sc_delta_count()};
    });
    return std::make_unique<CompletionWatcher>("user_design", acc, memory);
  });
  h.run(t.rays);
  const auto& watcher = *h.attached<CompletionWatcher>();
  const uint64_t cycles = h.accelerator().chip_counters().cycles;
  REQUIRE(h.finished.size() == t.rays.size());
  uint64_t last_finish = 0;
  for (const auto& [id, f] : h.finished) last_finish = std::max(last_finish, f.cycle);
  CHECK(last_finish == cycles);
  CHECK(h.accelerator().completed());

  const sc_core::sc_time expected = CycleClock(cfg.clock_mhz).period() * static_cast<double>(cycles);
  REQUIRE(watcher.seen.size() == 1);
  CHECK(watcher.seen[0].time == expected);
  CHECK(cb.calls == 1);
  CHECK(cb.cycles == cycles);
  CHECK(cb.at.time == expected);
  CHECK(cb.at.delta == watcher.seen[0].delta);  // notified immediately: the waiter ran in the same delta cycle
  CHECK(sc_core::sc_time_stamp() == expected);  // nothing else ran on: the run ended there
  return cycles;
}

uint64_t plain_run_cycles(const TraceInMemory& t, const HwConfig& cfg) {
  CycleRunOptions options;
  options.track_parents = false;  // as the harness runs
  return run_cycle_replay(feed_of(t.rays), t.sb.scene, t.sb.bvh, ReplayOptions{}, cfg, {}, options).counters.cycles;
}

}  // namespace

TEST_CASE("the completion event fires once at the last ray's finish and a plain run's cycles stay",
          "[module][completion]") {
  const TraceInMemory t = read_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  for (const char* preset : {"small", "large"})
    for (const char* memory : {"lt", "at", "ideal"})
      for (const uint32_t quantum : {1u, 256u, 4096u}) {
        INFO(preset << ", memory " << memory << ", quantum " << quantum);
        HwConfig cfg = load_preset(preset, "test");
        cfg.quantum_cycles = quantum;
        cfg.memory.ideal = std::string(memory) == "ideal";
        if (std::string(memory) == "at") cfg.memory.tlm = TlmStyle::ApproximatelyTimed;
        const uint64_t cycles = check_completion(t, cfg);
        CHECK(cycles == plain_run_cycles(t, cfg));
      }
}

TEST_CASE("the completion event fires at the last ray's finish with a memory target of the user's own",
          "[module][completion]") {
  const TraceInMemory t = read_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  BankedMemoryConfig bank;  // approximately timed, latency by open rows: responses in the target's own order
  bank.banks = 4;
  for (const uint32_t quantum : {1u, 256u}) {
    INFO("quantum " << quantum);
    HwConfig cfg = load_preset("small", "test");
    cfg.quantum_cycles = quantum;
    cfg.memory.tlm = TlmStyle::ApproximatelyTimed;
    check_completion(t, cfg, &bank);
  }
}

TEST_CASE("a run stopped early never notifies completion", "[module][completion]") {
  const TraceInMemory t = read_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  const std::atomic<bool> stop{true};
  int calls = 0;
  AcceleratorHarness h(t.sb.scene, t.sb.bvh, load_preset("small", "test"), ReplayOptions{}, {},
                       [&](Accelerator& acc) {
                         acc.set_stop_flag(&stop);
                         acc.set_completion_callback([&calls](uint64_t) { ++calls; });
                         return std::make_unique<CompletionWatcher>("user_design", acc);
                       });
  h.run(t.rays);
  CHECK(h.accelerator().partial());
  CHECK(h.finished.size() < t.rays.size());
  CHECK(calls == 0);
  CHECK(h.attached<CompletionWatcher>()->seen.empty());
  CHECK_FALSE(h.accelerator().completed());
}
