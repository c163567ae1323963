// Every unit's contract is checked, with an error naming the instance that
// broke it: an approximately timed target answering sooner than its lookahead
// promise (the built-in DRAM is refused at construction, a target of one's own
// when it happens), a dispatcher choosing a full or missing core, a memory
// answering a cycle in the past, a pipeline unit scheduling before its
// operands, a built-in pipeline asked for an operation ready in the past, and
// duplicate ray ids from a feed of one's own.
#include <catch2/catch.hpp>

#include <memory>

#include "../unit/three_floors.h"
#include "accelerator_harness.h"
#include "hw/core/pipeline_units.h"
#include "recording_memory.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;
using Catch::Matchers::Contains;

namespace {

/// One core, one slot, caches that miss on first touch, memory style `tlm`.
HwConfig cached(TlmStyle tlm) {
  HwConfig c = one_slot(1, 5, 11, 7);
  c.memory.ideal = false;
  c.memory.l1 = {256, 2, 64, 2, 2};
  c.memory.l2 = {1024, 4, 64, 3, 4};
  c.memory.dram_latency = 100;
  c.memory.dram_bytes_per_cycle = 64;
  c.memory.tlm = tlm;
  return c;
}

/// Always picks core `core`, free or not.
class StubbornDispatcher final : public sc_core::sc_module, public DispatchIf {
 public:
  StubbornDispatcher(sc_core::sc_module_name n, int core) : sc_core::sc_module(n), core_(core) {}
  int pick(const uint32_t*, uint32_t) override { return core_; }

 private:
  int core_;
};

/// Answers every read at the cycle it was issued (MemoryReadIf wants a later one).
class InstantMemory final : public sc_core::sc_module, public MemoryReadIf {
 public:
  explicit InstantMemory(sc_core::sc_module_name n) : sc_core::sc_module(n) {}
  uint64_t read(uint64_t, uint32_t, uint64_t now, uint32_t) override { return now; }
};

/// Issues every operation one cycle before its operands are ready.
class HastyTester final : public sc_core::sc_module, public TriangleTesterIf {
 public:
  explicit HastyTester(sc_core::sc_module_name n) : sc_core::sc_module(n) {}
  TriangleAnswer test_triangle(const TriangleOp& op) override {
    TriangleAnswer a;
    a.schedule = {op.ready - 1, op.ready + 10};
    return a;
  }
};

/// The datapath's answer on time, but a candidate at the interval's end (t = tmax).
class OutOfIntervalTester final : public sc_core::sc_module, public TriangleTesterIf {
 public:
  explicit OutOfIntervalTester(sc_core::sc_module_name n) : sc_core::sc_module(n) {}
  TriangleAnswer test_triangle(const TriangleOp& op) override {
    TriangleAnswer a;
    a.schedule = {op.ready, op.ready + 1};
    a.candidate = true;
    a.hit.t = op.tmax;
    return a;
  }
};

}  // namespace

TEST_CASE("an approximately timed lookahead the built-in DRAM cannot keep is refused, naming the field",
          "[module][contract]") {
  const ThreeFloors f;
  HwConfig cfg = cached(TlmStyle::ApproximatelyTimed);
  cfg.memory.at_lookahead_cycles = 101;  // the DRAM answers 100 cycles after a request
  CHECK_THROWS_WITH(AcceleratorHarness(f.scene, f.bvh, cfg, ReplayOptions{}),
                    Contains("memory.at_lookahead_cycles: 101 is more than memory.dram_latency (100)"));
  cfg.memory.at_lookahead_cycles = 100;
  AcceleratorHarness h(f.scene, f.bvh, cfg, ReplayOptions{});
  h.run({down_from(1, 1.0f)});
  CHECK(h.finished.at(1).prim == 0);
}

TEST_CASE("a target of one's own that answers sooner than the lookahead promises stops the run, named",
          "[module][contract]") {
  const ThreeFloors f;
  for (const uint32_t lookahead : {100u, 101u, 1000u}) {
    INFO("lookahead " << lookahead);
    HwConfig cfg = cached(TlmStyle::ApproximatelyTimed);
    cfg.slots_per_core = 4;
    cfg.memory.at_lookahead_cycles = lookahead;
    AcceleratorUnits units;
    units.external_memory = true;
    AcceleratorHarness h(f.scene, f.bvh, cfg, ReplayOptions{}, units,
                         [&cfg](Accelerator& acc) -> std::unique_ptr<sc_core::sc_module> {
                           auto m = std::make_unique<RecordingMemory>("my_memory", CycleClock(cfg.clock_mhz).period(),
                                                                      100);
                           acc.memory_socket().bind(m->socket);
                           return m;
                         });
    // A ray that reads the BVH, then 300 that miss the scene at the root box
    // (no read): the scheduler has work past the first read's answer and runs
    // ahead as far as it was promised.
    std::vector<TraceRay> rays = {down_from(1, 1.0f)};
    for (int64_t id = 2; id < 302; ++id) {
      rays.push_back(down_from(id, 1.0f));
      rays.back().d = {0, 0, 1};
    }
    if (lookahead == 100) {
      h.run(rays);
      CHECK(h.finished.size() == rays.size());
    } else {
      CHECK_THROWS_WITH(h.run(rays),
                        Contains("my_memory: answered the read of 0x0 sent at cycle 11 for cycle 111") &&
                            Contains("memory.at_lookahead_cycles = " + std::to_string(lookahead)));
    }
  }
}

TEST_CASE("a dispatcher of one's own that picks a full or missing core stops the run, named", "[module][contract]") {
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);
  cfg.cores = 2;
  for (const int core : {0, 2, -3}) {
    INFO("core " << core);
    AcceleratorUnits units;
    units.dispatcher = [core](const char* name, const HwConfig&) {
      return std::make_unique<StubbornDispatcher>(name, core);
    };
    AcceleratorHarness h(f.scene, f.bvh, cfg, ReplayOptions{}, units);
    // Core 0 has one slot: the second ray finds it full.
    CHECK_THROWS_WITH(h.run({down_from(1, 1.0f), down_from(2, 1.0f)}),
                      Contains("accelerator.dispatcher: DispatchIf::pick chose core " + std::to_string(core)) &&
                          Contains(core == 0 ? "has no free slot" : "does not exist (the accelerator has 2 cores)"));
  }
}

TEST_CASE("a memory of one's own answering the cycle of the read stops the run, named", "[module][contract]") {
  const ThreeFloors f;
  AcceleratorUnits units;
  units.l1_cache = [](const char* name, uint32_t, const HwConfig&) { return std::make_unique<InstantMemory>(name); };
  HwConfig cfg = one_slot(1, 5, 11, 7);
  cfg.memory.ideal = false;
  AcceleratorHarness h(f.scene, f.bvh, cfg, ReplayOptions{}, units);
  CHECK_THROWS_WITH(h.run({down_from(1, 1.0f)}),
                    Contains("accelerator.core_0.l1_cache: a read of 64 bytes at 0x0 issued at cycle 6 was answered "
                             "cycle 6"));
}

TEST_CASE("a pipeline unit of one's own issuing before its operands stops the run, named", "[module][contract]") {
  const ThreeFloors f;
  AcceleratorUnits units;
  units.triangle_tester = [](const char* name, uint32_t, const HwConfig&) {
    return std::make_unique<HastyTester>(name);
  };
  AcceleratorHarness h(f.scene, f.bvh, one_slot(1, 5, 11, 7), ReplayOptions{}, units);
  CHECK_THROWS_WITH(h.run({down_from(1, 1.0f)}),
                    Contains("accelerator.core_0.triangle_tester: an operation ready at cycle") &&
                        Contains("must answer issue >= ready"));
}

TEST_CASE("a triangle tester of one's own answering a candidate outside the interval stops the run, named",
          "[module][contract]") {
  const ThreeFloors f;
  AcceleratorUnits units;
  units.triangle_tester = [](const char* name, uint32_t, const HwConfig&) {
    return std::make_unique<OutOfIntervalTester>(name);
  };
  AcceleratorHarness h(f.scene, f.bvh, one_slot(1, 5, 11, 7), ReplayOptions{}, units);
  CHECK_THROWS_WITH(h.run({down_from(1, 1.0f)}),
                    Contains("accelerator.core_0.triangle_tester: triangle") &&
                        Contains("outside the ray's interval"));
}

TEST_CASE("a built-in pipeline asked for an operation ready in the past names itself", "[module][contract]") {
  const SimulationContext context;
  BoxUnit box("my_box", UnitConfig{1, 8, 1});
  box.schedule_inline(1000, 1000);  // the current event moves to cycle 1000
  CHECK_THROWS_WITH(box.schedule_inline(10, 1000), Contains("my_box: an operation ready at cycle"));
}

TEST_CASE("duplicate ray ids from a feed of one's own stop the run, naming the position", "[module][contract]") {
  const ThreeFloors f;
  AcceleratorHarness h(f.scene, f.bvh, one_slot(1, 5, 11, 7), ReplayOptions{});
  CHECK_THROWS_WITH(h.run({down_from(1, 1.0f), down_from(2, 1.0f), down_from(1, 1.0f)}),
                    Contains("trace position 2: duplicate id 1: the ray at trace position 0 has it too"));
  AcceleratorHarness dense(f.scene, f.bvh, one_slot(1, 5, 11, 7), ReplayOptions{});
  CHECK_THROWS_WITH(dense.run({down_from(7, 1.0f), down_from(8, 1.0f), down_from(9, 1.0f), down_from(8, 1.0f)}),
                    Contains("trace position 3: duplicate id 8: the ray at trace position 1 has it too"));
}
