// The accelerator's TLM-2.0 memory boundary with targets other than its
// built-in loosely timed DRAM: an approximately timed banked memory written
// here (latency depending on open rows), the built-in DRAM in approximately
// timed style, a target that never answers, and the scheduler's lookahead.
// Cycles computed by hand on the three-floor BVH (one core, one slot, cold
// caches: every node and leaf read goes to the memory target).
#include <catch2/catch.hpp>

#include <map>
#include <string>

#include "accelerator_harness.h"
#include "banked_memory.h"
#include "bench/functional_bench.h"
#include "datapath/self_intersection_method.h"
#include "scene/scene.h"
#include "../unit/three_floors.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

constexpr uint32_t kLb = 5, kLt = 11, kH1 = 2, kH2 = 3;

/// One core, one slot, the three floors' latencies; caches that miss on first
/// touch (L1 hit 2, L2 hit 3), memory style `tlm`.
HwConfig cached_one_slot(TlmStyle tlm) {
  HwConfig c = one_slot(1, kLb, kLt, 7);
  c.memory.ideal = false;
  c.memory.l1 = {256, 2, 64, kH1, 2};
  c.memory.l2 = {1024, 4, 64, kH2, 4};
  c.memory.dram_latency = 100;
  c.memory.dram_bytes_per_cycle = 64;  // a line per cycle: no queueing for lone reads
  c.memory.tlm = tlm;
  return c;
}

/// A memory target that takes every request and never answers.
class SilentMemory final : public sc_core::sc_module, public tlm::tlm_fw_transport_if<> {
 public:
  tlm::tlm_target_socket<> socket;
  explicit SilentMemory(sc_core::sc_module_name n) : sc_core::sc_module(n), socket("socket") { socket.bind(*this); }
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload&, tlm::tlm_phase& phase, sc_core::sc_time&) override {
    phase = tlm::END_REQ;
    return tlm::TLM_UPDATED;
  }
  void b_transport(tlm::tlm_generic_payload&, sc_core::sc_time&) override {}
  bool get_direct_mem_ptr(tlm::tlm_generic_payload&, tlm::tlm_dmi&) override { return false; }
  unsigned int transport_dbg(tlm::tlm_generic_payload&) override { return 0; }
};

AcceleratorHarness::Attach banked(const BankedMemoryConfig& c, double clock_mhz) {
  return [c, clock_mhz](Accelerator& acc) -> std::unique_ptr<sc_core::sc_module> {
    auto m = std::make_unique<BankedMemory>("banked_memory", c, CycleClock(clock_mhz).period());
    acc.memory_socket().bind(m->socket);
    return m;
  };
}

}  // namespace

TEST_CASE("an approximately timed banked memory gives the hand-computed cycles, open rows included",
          "[module][tlm]") {
  const ThreeFloors f;
  for (const uint32_t lines_per_row : {4u, 1u}) {
    INFO(lines_per_row << " lines per row");
    BankedMemoryConfig bank;
    bank.banks = 2;
    bank.lines_per_row = lines_per_row;
    bank.row_hit = 12;
    bank.row_miss = 40;
    const HwConfig cfg = cached_one_slot(TlmStyle::ApproximatelyTimed);
    AcceleratorUnits units;
    units.external_memory = true;
    AcceleratorHarness h(f.scene, f.bvh, cfg, ReplayOptions{}, units, banked(bank, cfg.clock_mhz));
    h.run({down_from(1, 1.0f)});
    REQUIRE(h.finished.at(1).prim == 0);
    // Dispatched at 1; root box done at 6. Each read misses L1 and L2 and leaves
    // for the memory 2 + 3 cycles after it is asked.
    //   node 0, line 0: bank 0, row 0 closed: sent 6 + 5 = 11, data 11 + 40 = 51, boxes done 56
    //   node 1, line 1: bank 1, row 0 closed: sent 61, data 101, boxes done 106
    //   leaf [prim 0] at byte 128, line 2: bank 0, row 2 / (2 x lines_per_row):
    //     4 lines a row: row 0, open: sent 111, data 123, triangle done 134
    //     1 line a row:  row 1, a miss: sent 111, data 151, triangle done 162
    const uint64_t want = lines_per_row == 4 ? 134 : 162;
    CHECK(h.finished.at(1).cycle == want);
    const BankedMemory& m = *h.attached<BankedMemory>();
    CHECK(m.row_misses == (lines_per_row == 4 ? 2u : 3u));
    CHECK(m.row_hits == (lines_per_row == 4 ? 1u : 0u));
    CHECK(h.accelerator().l2()->dram_requests() == 3);
    // The scheduler kept SystemC time with the target: the run ends on the last cycle.
    CHECK(h.accelerator().systemc_run().cycles == want);
  }
}

TEST_CASE("the built-in DRAM gives the same cycles loosely and approximately timed when reads do not overlap",
          "[module][tlm]") {
  const ThreeFloors f;
  uint64_t finish[2];
  for (const TlmStyle style : {TlmStyle::LooselyTimed, TlmStyle::ApproximatelyTimed}) {
    AcceleratorHarness h(f.scene, f.bvh, cached_one_slot(style), ReplayOptions{});
    h.run({down_from(1, 1.0f)});
    REQUIRE(h.finished.at(1).prim == 0);
    finish[style == TlmStyle::ApproximatelyTimed] = h.finished.at(1).cycle;
  }
  // As above with 100 cycles for every line: sent 11, 111 + 5 ... : node 0 data 111,
  // boxes 116; node 1 sent 121, data 221, boxes 226; leaf sent 231, data 331, done 342.
  CHECK(finish[0] == 342);
  CHECK(finish[1] == 342);
}

TEST_CASE("approximately timed memory on many rays: the same hits as the functional replay, every ray finished",
          "[module][tlm]") {
  const Scene scene = load_scene(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj");
  const Bvh bvh = build_bvh(scene);
  const std::vector<TraceRay> rays = bench_rays(scene, 600, 5);
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method("validity-bit", opt.method, err));
  FunctionalReplayer functional(scene, bvh, opt);
  std::map<int64_t, int32_t> want;
  for (const TraceRay& r : rays) want[r.id] = functional.replay(r).hit.prim;
  std::map<int64_t, Finished> lockstep;
  uint64_t lockstep_activations = 0;
  // The banked memory answers 12 cycles after a request at the soonest: a
  // lookahead of 12 lets the scheduler run ahead of it without moving a cycle.
  for (const uint32_t lookahead : {1u, 12u}) {
    INFO("lookahead " << lookahead);
    HwConfig cfg = load_preset("small", "test");
    cfg.memory.tlm = TlmStyle::ApproximatelyTimed;
    cfg.memory.at_lookahead_cycles = lookahead;
    BankedMemoryConfig bank;
    bank.banks = 8;
    AcceleratorUnits units;
    units.external_memory = true;
    AcceleratorHarness h(scene, bvh, cfg, opt, units, banked(bank, cfg.clock_mhz));
    h.run(rays);
    REQUIRE(h.finished.size() == rays.size());
    size_t differ = 0;
    for (const auto& [id, fin] : h.finished) differ += fin.prim != want.at(id);
    CHECK(differ == 0);
    CHECK(h.accelerator().l2()->dram_requests() > 100);
    if (lookahead == 1) {
      lockstep = h.finished;
      lockstep_activations = h.accelerator().systemc_run().activations;
      continue;
    }
    size_t moved = 0;
    for (const auto& [id, fin] : h.finished) moved += fin.cycle != lockstep.at(id).cycle;
    CHECK(moved == 0);
    CHECK(h.accelerator().systemc_run().activations < lockstep_activations);
  }
}

TEST_CASE("a memory target that never answers stops the run with a report of the waiting slot", "[module][tlm]") {
  const ThreeFloors f;
  AcceleratorUnits units;
  units.external_memory = true;
  AcceleratorHarness h(f.scene, f.bvh, cached_one_slot(TlmStyle::ApproximatelyTimed), ReplayOptions{}, units,
                       [](Accelerator& acc) -> std::unique_ptr<sc_core::sc_module> {
                         auto m = std::make_unique<SilentMemory>("silent_memory");
                         acc.memory_socket().bind(m->socket);
                         return m;
                       });
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(h.run({down_from(1, 1.0f)}), Contains("stopped making progress") &&
                                                     Contains("accelerator.core_0 slot 0: ray 1") &&
                                                     Contains("waiting since cycle 6 for a read") &&
                                                     Contains("1 DRAM requests in flight (sent at cycles 11)"));
}
