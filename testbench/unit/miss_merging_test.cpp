// Merging of misses in flight on and off (memory.l1.merge_misses,
// memory.l2.merge_misses): latencies and counts computed by hand from
// docs/memory-model.md, "Misses in flight (MSHRs)".
#include <catch2/catch.hpp>

#include "memory_rig.h"

using namespace vbsim::hw;
using vbsim::hw::test::make_memory;

namespace {

// memory_rig.h's small hierarchy (L1: 2 sets x 2 ways, hit 2, 2 MSHRs; L2: 4
// sets x 4 ways, hit 10, 4 MSHRs; DRAM 100 cycles) on a channel so fast that
// lines never queue. A line from DRAM: 2 + 10 + 100 = 112 cycles.
MemoryConfig base(bool l1_merges, bool l2_merges) {
  MemoryConfig m = vbsim::hw::test::fast_channel_config();
  m.l1.merge_misses = l1_merges;
  m.l2.merge_misses = l2_merges;
  return m;
}

}  // namespace

TEST_CASE("a second request for a line in flight merges, or misses again with merging off", "[memory][merging]") {
  SECTION("both levels merge (the default): the L1 merges it, one DRAM read") {
    auto mem = make_memory(base(true, true), 1);
    CHECK(mem->read(0, 0, 64, 0) == 112);
    CHECK(mem->read(0, 0, 64, 5) == 112);
    const auto s = mem->stats();
    CHECK(s["l1"]["merges"] == 1);
    CHECK(s["l1"]["misses"] == 1);
    CHECK(s["dram"]["reads"] == 1);
  }
  SECTION("the L1 does not merge: its second miss reaches the L2 at 7 and merges there") {
    auto mem = make_memory(base(false, true), 1);
    CHECK(mem->read(0, 0, 64, 0) == 112);
    CHECK(mem->read(0, 0, 64, 5) == 112);
    const auto s = mem->stats();
    CHECK(s["l1"]["merges"] == 0);
    CHECK(s["l1"]["misses"] == 2);
    CHECK(s["l2"]["merges"] == 1);
    CHECK(s["dram"]["reads"] == 1);
  }
  SECTION("neither merges: a second DRAM read leaves the L2 at 17 and arrives at 117") {
    auto mem = make_memory(base(false, false), 1);
    CHECK(mem->read(0, 0, 64, 0) == 112);
    CHECK(mem->read(0, 0, 64, 5) == 117);
    // The line's first fill stands: at 113 it is a hit, not a wait for the second.
    CHECK(mem->read(0, 0, 64, 113) == 115);
    const auto s = mem->stats();
    CHECK(s["l1"]["misses"] == 2);
    CHECK(s["l1"]["hits"] == 1);
    CHECK(s["l2"]["misses"] == 2);
    CHECK(s["l2"]["merges"] == 0);
    CHECK(s["dram"]["reads"] == 2);
  }
  SECTION("without merging each request takes an MSHR: the third waits for the first fill") {
    auto mem = make_memory(base(false, true), 1);
    CHECK(mem->read(0, 0, 64, 0) == 112);
    CHECK(mem->read(0, 0, 64, 1) == 112);
    // Both MSHRs held until 112: it leaves then, finds the line filled in the L2 at 114: 124.
    CHECK(mem->read(0, 0, 64, 2) == 124);
    CHECK(mem->stats()["l1"]["mshr_stall_cycles"] == 110);
  }
  SECTION("merging on, the same three requests cost one MSHR") {
    auto mem = make_memory(base(true, true), 1);
    for (uint64_t t : {0u, 1u, 2u}) CHECK(mem->read(0, 0, 64, t) == 112);
    CHECK(mem->stats()["l1"]["mshr_stall_cycles"] == 0);
  }
}
