// Units of the accelerator replaced by modules written here, bound through the
// same interfaces: an unpipelined box unit (answering the datapath's result), a
// dispatcher that fills one core first, an L1 replaced by a fixed-latency
// memory and a result sink of one's own. Cycles computed by hand; the hits stay
// the datapath's.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <memory>

#include "../unit/three_floors.h"
#include "accelerator_harness.h"
#include "hw/observe/hierarchy_report.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

/// A box unit that holds its one datapath for the whole latency of an
/// operation (no pipelining): an operation issues when both its operands and
/// the unit are free.
class UnpipelinedBoxUnit final : public sc_core::sc_module, public BoxUnitIf {
 public:
  UnpipelinedBoxUnit(sc_core::sc_module_name n, uint32_t latency) : sc_core::sc_module(n), latency_(latency) {}
  BoxAnswer test_boxes(const BoxOp& op) override {
    BoxAnswer a = BoxUnit::compute(op);  // the datapath's answer
    const uint64_t issue = std::max(op.ready, free_);
    free_ = issue + latency_;
    ++ops;
    a.schedule = {issue, issue + latency_};
    return a;
  }
  uint64_t ops = 0;

 private:
  uint32_t latency_;
  uint64_t free_ = 0;
};

/// Every ray to the lowest-numbered core with a free slot.
class FirstFitDispatcher final : public sc_core::sc_module, public DispatchIf {
 public:
  explicit FirstFitDispatcher(sc_core::sc_module_name n) : sc_core::sc_module(n) {}
  int pick(const uint32_t* free_slots, uint32_t cores) override {
    for (uint32_t c = 0; c < cores; ++c)
      if (free_slots[c]) return static_cast<int>(c);
    return -1;
  }
};

/// A core's whole memory: every read takes `latency` cycles.
class FixedLatencyMemory final : public sc_core::sc_module, public MemoryReadIf {
 public:
  FixedLatencyMemory(sc_core::sc_module_name n, uint32_t latency) : sc_core::sc_module(n), latency_(latency) {}
  uint64_t read(uint64_t, uint32_t, uint64_t now, uint32_t) override { return now + latency_; }

 private:
  uint32_t latency_;
};

/// A ray that misses the scene: its search ends with the root box test.
TraceRay up_from(int64_t id) {
  TraceRay r = down_from(id, 1.0f);
  r.d = {0, 0, 1};
  return r;
}

}  // namespace

TEST_CASE("an unpipelined box unit in place of the built-in one serialises the root box tests", "[module][swap]") {
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);
  cfg.slots_per_core = 3;
  for (const bool replaced : {false, true}) {
    INFO((replaced ? "replaced" : "built-in"));
    AcceleratorUnits units;
    if (replaced)
      units.box_unit = [](const char* name, uint32_t, const HwConfig& c) {
        return std::make_unique<UnpipelinedBoxUnit>(name, c.box.latency);
      };
    AcceleratorHarness h(f.scene, f.bvh, cfg, ReplayOptions{}, units);
    h.run({up_from(1), up_from(2), up_from(3)});
    // Ray k is emitted by cycle k and dispatched then; its root box test is its
    // whole search. Pipelined: issue k, done k + 5. Unpipelined: issue at the
    // later of k and the previous test's end: 1-6, 6-11, 11-16.
    for (int64_t k = 1; k <= 3; ++k) {
      CHECK(h.finished.at(k).prim == -1);
      CHECK(h.finished.at(k).cycle == (replaced ? 1 + 5 * static_cast<uint64_t>(k) : static_cast<uint64_t>(k) + 5));
    }
    const std::string tree = hierarchy_text(h.accelerator());
    CHECK_THAT(tree, Catch::Matchers::Contains(replaced ? "box_unit  [UnpipelinedBoxUnit]" : "box_unit  [BoxUnit]"));
    // The scheduler counts the replacement's operations and waits from its
    // answers (rays 2 and 3 wait 6 - 2 and 11 - 3 cycles); its utilisation is
    // its own business (null).
    const HwCounters c = h.accelerator().chip_counters();
    CHECK(c.box.ops == 3);
    CHECK(c.box.wait_cycles == (replaced ? 4 + 8 : 0));
    CHECK(c.box.replaced == replaced);
    const nlohmann::json hw = h.accelerator().hw_json();
    CHECK(hw["units"]["box"]["utilisation"].is_null() == replaced);
    CHECK(hw["units"]["triangle"]["utilisation"].is_number());
  }
}

TEST_CASE("a dispatcher of one's own decides which core each ray goes to", "[module][swap]") {
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);
  cfg.cores = 2;
  cfg.slots_per_core = 2;
  cfg.dispatch = DispatchPolicy::RoundRobin;
  for (const bool replaced : {false, true}) {
    AcceleratorUnits units;
    if (replaced)
      units.dispatcher = [](const char* name, const HwConfig&) { return std::make_unique<FirstFitDispatcher>(name); };
    AcceleratorHarness h(f.scene, f.bvh, cfg, ReplayOptions{}, units);
    h.run({up_from(1), up_from(2)});
    // Round robin: one ray a core; first fit: both on core 0.
    CHECK(h.accelerator().core(0).counters.rays == (replaced ? 2u : 1u));
    CHECK(h.accelerator().core(1).counters.rays == (replaced ? 0u : 1u));
  }
}

TEST_CASE("an L1 replaced by a fixed-latency memory times every read alike", "[module][swap]") {
  const ThreeFloors f;
  HwConfig cfg = one_slot(1, 5, 11, 7);
  cfg.memory.ideal = false;  // the caches' configuration is built, but core 0's memory is replaced
  AcceleratorUnits units;
  units.l1_cache = [](const char* name, uint32_t, const HwConfig&) {
    return std::make_unique<FixedLatencyMemory>(name, 9);
  };
  AcceleratorHarness h(f.scene, f.bvh, cfg, ReplayOptions{}, units);
  h.run({down_from(1, 1.0f)});
  // As with an ideal memory of latency 9: 1 + 5 + (9 + 5) + (9 + 5) + (9 + 11).
  CHECK(h.finished.at(1).prim == 0);
  CHECK(h.finished.at(1).cycle == 1 + 5 + 14 + 14 + 20);
  CHECK(h.accelerator().l2()->dram_requests() == 0);
}

namespace {

/// Where finished rays go: their hit and finish cycle, by id.
class RecordingSink final : public sc_core::sc_module, public ResultSinkIf {
 public:
  RecordingSink(sc_core::sc_module_name n, std::map<int64_t, Finished>& out) : sc_core::sc_module(n), out_(out) {}
  void ray_done(const TraceRay& tr, const EmittedRay&, const Hit& hit, uint64_t, uint64_t, uint64_t now,
                uint64_t) override {
    out_[tr.id] = {hit.prim, now};
  }

 private:
  std::map<int64_t, Finished>& out_;
};

}  // namespace

TEST_CASE("a result sink of one's own receives every finished ray at the built-in sink's cycle", "[module][swap]") {
  const ThreeFloors f;
  const HwConfig cfg = one_slot(3, 5, 11, 7);
  AcceleratorHarness builtin(f.scene, f.bvh, cfg, ReplayOptions{});
  builtin.run({down_from(1, 1.0f), up_from(2), down_from(3, 0.5f)});
  std::map<int64_t, Finished> seen;
  AcceleratorUnits units;
  units.result_sink = [&seen](const char* name, const HwConfig&) { return std::make_unique<RecordingSink>(name, seen); };
  AcceleratorHarness h(f.scene, f.bvh, cfg, ReplayOptions{}, units);
  h.run({down_from(1, 1.0f), up_from(2), down_from(3, 0.5f)});
  REQUIRE(seen.size() == 3);
  CHECK(h.finished.empty());  // the replacement took the rays in place of the conclusion and its callback
  for (const int64_t id : {1, 2, 3}) {
    CHECK(seen.at(id).prim == builtin.finished.at(id).prim);
    CHECK(seen.at(id).cycle == builtin.finished.at(id).cycle);
  }
  CHECK(seen.at(1).prim == 0);   // down onto the top floor
  CHECK(seen.at(2).prim == -1);  // up: a miss
  // The accounting stays: the run's cycles are the last ray's finish.
  CHECK(h.accelerator().chip_counters().cycles == builtin.accelerator().chip_counters().cycles);
  CHECK(h.accelerator().chip_counters().rays == 3);
  const std::string tree = hierarchy_text(h.accelerator());
  CHECK_THAT(tree, Catch::Matchers::Contains("result_sink  [RecordingSink]"));
  CHECK_THAT(tree, Catch::Matchers::Contains("result_accounting  [ResultSink]"));
}
