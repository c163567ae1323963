// Two throughput knobs of the memory system, against latencies computed by hand
// (docs/memory-model.md): the DRAM's latency per byte read and the L1's ports.
#include <catch2/catch.hpp>

#include "memory_rig.h"

using namespace vbsim::hw;
using vbsim::hw::test::make_memory;

namespace {

/// memory_rig.h's small hierarchy with a channel so fast that lines never queue:
/// L1 hit 2, L2 hit 12, DRAM 112 cycles.
MemoryConfig base() { return vbsim::hw::test::fast_channel_config(); }

}  // namespace

TEST_CASE("DRAM latency per byte adds whole cycles per line request", "[memory][dram]") {
  MemoryConfig m = base();
  SECTION("0.5 cycles a byte: 32 cycles more for a 64-byte line") {
    m.dram_latency_per_byte = 0.5;
    CHECK(dram_line_latency(m) == 132);
    auto mem = make_memory(m, 1);
    CHECK(mem->read(0, 0, 64, 0) == 2 + 10 + 132);
    CHECK(mem->read(0, 64, 64, 1000) == 1000 + 2 + 10 + 132);  // every line pays it
    CHECK(mem->read(0, 0, 64, 2000) == 2002);                     // an L1 hit does not
  }
  SECTION("0.1 cycles a byte: 6.4 rounds up to 7") {
    m.dram_latency_per_byte = 0.1;
    CHECK(dram_line_latency(m) == 107);
    CHECK(make_memory(m, 1)->read(0, 0, 64, 0) == 2 + 10 + 107);
  }
  SECTION("a per-byte latency alone, as a DRAM that streams bytes (rtcore-systemc's 5 cycles a byte)") {
    m.dram_latency = 1;
    m.dram_latency_per_byte = 5;
    m.l1.line_bytes = m.l2.line_bytes = 32;
    CHECK(dram_line_latency(m) == 1 + 160);
    CHECK(make_memory(m, 1)->read(0, 0, 32, 0) == 2 + 10 + 161);
  }
  SECTION("a negative or non-finite value is refused") {
    m.dram_latency_per_byte = -1;
    CHECK_THROWS_WITH(make_memory(m, 1), Catch::Contains("memory.dram_latency_per_byte"));
  }
}

TEST_CASE("L1 ports limit the reads a core's L1 takes at once", "[memory][ports]") {
  MemoryConfig m = base();
  SECTION("no limit (the default): reads at one cycle all hit at once") {
    auto mem = make_memory(m, 1);
    mem->read(0, 0, 64, 0);  // the line comes at 112
    for (int i = 0; i < 4; ++i) CHECK(mem->read(0, 0, 64, 200) == 202);
  }
  SECTION("one port taking a read every 2 cycles: 202, 204, 206") {
    m.l1.ports = 1;
    m.l1.port_cycles = 2;
    auto mem = make_memory(m, 1);
    CHECK(mem->read(0, 0, 64, 0) == 112);
    CHECK(mem->read(0, 0, 64, 200) == 202);
    CHECK(mem->read(0, 0, 64, 200) == 204);
    CHECK(mem->read(0, 8, 40, 200) == 206);
    CHECK(mem->read(0, 0, 64, 201) == 208);  // a later read queues behind them
    CHECK(mem->read(0, 0, 64, 300) == 302);  // the port is free again
    // Waits: 0 + 2 + 4 + 5 + 0.
    const auto inst = mem->accelerator().core(0).l1()->stat_values();
    CHECK(inst["port_wait_cycles"] == 11);
  }
  SECTION("two ports taking a read every 3 cycles: pairs at 202, 205, 208") {
    m.l1.ports = 2;
    m.l1.port_cycles = 3;
    auto mem = make_memory(m, 1);
    mem->read(0, 0, 64, 0);
    const uint64_t expected[] = {202, 202, 205, 205, 208};
    for (uint64_t e : expected) CHECK(mem->read(0, 0, 64, 200) == e);
  }
  SECTION("a miss leaves when its port takes it: the DRAM round starts later") {
    m.l1.ports = 1;
    m.l1.port_cycles = 4;
    auto mem = make_memory(m, 1);
    CHECK(mem->read(0, 0, 64, 0) == 112);
    CHECK(mem->read(0, 64, 64, 0) == 4 + 112);  // taken at 4, then L1 miss, L2 miss, DRAM
  }
  SECTION("each core's L1 has its own ports") {
    m.l1.ports = 1;
    m.l1.port_cycles = 5;
    auto mem = make_memory(m, 2);
    mem->read(0, 0, 64, 0);
    mem->read(1, 0, 64, 0);  // the L2 merges it: 112
    CHECK(mem->read(0, 0, 64, 200) == 202);
    CHECK(mem->read(1, 0, 64, 200) == 202);
    CHECK(mem->read(0, 0, 64, 200) == 207);
  }
}
