// The L1/L2/DRAM hierarchy of the accelerator's memory modules (L1Cache,
// L2Cache, the Dram target behind the TLM-2.0 socket): latencies computed by
// hand from the composition in docs/memory-model.md, merging of misses in flight, MSHR,
// outstanding-request and bandwidth stalls, and a cross-check of the hit/miss
// sequence against explicit LRU lists.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "memory_rig.h"
#include "lru_reference.h"

using namespace vbsim::hw;
using vbsim::hw::test::make_memory;
using vbsim::hw::test::MemoryRig;
using vbsim::hw::test::fast_channel_config;
using vbsim::hw::test::small_config;

namespace {

constexpr uint64_t kLine = 64;

}  // namespace

TEST_CASE("Memory hierarchy first read goes to DRAM and the second hits L1", "[memory][hierarchy]") {
  auto mem = make_memory(small_config(), 2);
  CHECK(mem->read(0, 0, 64, 0) == 0 + 2 + 10 + 100);
  CHECK(mem->read(0, 0, 64, 200) == 202);
  CHECK(mem->read(0, 8, 40, 300) == 302);  // a triangle inside the same line
  const auto s = mem->stats();
  CHECK(s["model"] == "hierarchy");
  CHECK(s["l1"]["accesses"] == 3);
  CHECK(s["l1"]["hits"] == 2);
  CHECK(s["l1"]["misses"] == 1);
  CHECK(s["l1"]["per_core"][0]["hits"] == 2);
  CHECK(s["l1"]["per_core"][1]["accesses"] == 0);
  CHECK(s["l2"]["accesses"] == 1);
  CHECK(s["l2"]["misses"] == 1);
  CHECK(s["dram"]["reads"] == 1);
  CHECK(s["dram"]["bytes"] == 64);
  CHECK(s["reads"] == 3);
  CHECK(s["bytes"] == 64 + 64 + 40);
}

TEST_CASE("Memory hierarchy L1 misses that hit L2 follow LRU order", "[memory][hierarchy]") {
  auto mem = make_memory(small_config(), 1);
  // Lines 0, 2, 4 share L1 set 0 (2 ways); L2 (4 ways) keeps all three.
  CHECK(mem->read(0, 0 * kLine, 64, 0) == 112);
  CHECK(mem->read(0, 2 * kLine, 64, 1000) == 1112);
  CHECK(mem->read(0, 4 * kLine, 64, 2000) == 2112);  // evicts 0 from L1
  CHECK(mem->read(0, 0 * kLine, 64, 3000) == 3012);  // L2 hit; its fill evicts 2 (older than 4)
  CHECK(mem->read(0, 2 * kLine, 64, 4000) == 4012);  // L2 hit; its fill evicts 4 (older than 0)
  CHECK(mem->read(0, 0 * kLine, 64, 5000) == 5002);  // 0 stayed
  CHECK(mem->read(0, 4 * kLine, 64, 6000) == 6012);
  const auto s = mem->stats();
  CHECK(s["l1"]["hits"] == 1);
  CHECK(s["l2"]["hits"] == 3);
  CHECK(s["l2"]["misses"] == 3);
  CHECK(s["l2"]["hit_rate"].get<double>() == Approx(0.5));
}

TEST_CASE("Memory hierarchy merges reads of a line in flight and shows it from its fill cycle", "[memory][hierarchy]") {
  auto mem = make_memory(small_config(), 2);
  CHECK(mem->read(0, 0, 64, 0) == 112);
  CHECK(mem->read(0, 16, 8, 5) == 112);    // same L1 MSHR
  CHECK(mem->read(1, 0, 64, 6) == 112);    // core 1 misses its L1, merges in L2 (arrives at 8)
  CHECK(mem->read(0, 0, 64, 111) == 112);  // one cycle before the fill: still in flight
  CHECK(mem->read(0, 0, 64, 112) == 114);  // at the fill cycle: a hit
  CHECK(mem->read(1, 0, 64, 112) == 114);
  const auto s = mem->stats();
  CHECK(s["l1"]["merges"] == 2);
  CHECK(s["l1"]["misses"] == 2);
  CHECK(s["l1"]["hits"] == 2);
  CHECK(s["l2"]["merges"] == 1);
  CHECK(s["l2"]["misses"] == 1);
  CHECK(s["dram"]["reads"] == 1);
}

TEST_CASE("Memory hierarchy L2 merges a miss arriving just before the fill", "[memory][hierarchy]") {
  auto mem = make_memory(small_config(), 2);
  CHECK(mem->read(0, 0, 64, 0) == 112);
  CHECK(mem->read(1, 0, 64, 105) == 112);  // reaches L2 at 107, five cycles before the fill
  CHECK(mem->read(1, 0, 64, 110) == 112);  // core 1's own miss is in flight now
  CHECK(mem->read(1, 64 * 4, 64, 110) == 222);  // another line, L2 miss: 110 + 112
  CHECK(mem->read(0, 0, 64, 112) == 114);
  const auto s = mem->stats();
  CHECK(s["l2"]["merges"] == 1);
  CHECK(s["l2"]["hits"] == 0);
}

TEST_CASE("Memory hierarchy read spanning two lines is ready with its last line", "[memory][hierarchy]") {
  auto mem = make_memory(small_config(), 1);
  // Bytes 60..67: lines 0 and 1, both to DRAM at cycle 12; line 1 waits 4 cycles for the channel.
  CHECK(mem->read(0, 60, 8, 0) == 116);
  CHECK(mem->read(0, 64, 8, 200) == 202);
  CHECK(mem->stats()["line_requests"] == 3);
}

TEST_CASE("Memory hierarchy L1 MSHRs full delay a miss until the first frees", "[memory][hierarchy]") {
  auto mem = make_memory(fast_channel_config(), 1);  // 2 L1 MSHRs
  CHECK(mem->read(0, 3 * kLine, 64, 0) == 112);    // line 3 into L1 for later
  CHECK(mem->read(0, 0 * kLine, 64, 1000) == 1112);
  CHECK(mem->read(0, 1 * kLine, 64, 1000) == 1112);
  CHECK(mem->read(0, 3 * kLine, 64, 1000) == 1002);  // a hit does not wait for an MSHR
  CHECK(mem->read(0, 0 * kLine, 8, 1001) == 1112);   // nor does a merge
  // Both MSHRs busy until 1112: starts then, 1112 + 112.
  CHECK(mem->read(0, 2 * kLine, 64, 1000 + 2) == 1224);
  // The next miss takes the other MSHR, also free at 1112.
  CHECK(mem->read(0, 5 * kLine, 64, 1003) == 1224);
  // Now both are held until 1224.
  CHECK(mem->read(0, 7 * kLine, 64, 1004) == 1336);
  const auto s = mem->stats();
  CHECK(s["stall_cycles"]["l1_mshr_full"] == (1112 - 1002) + (1112 - 1003) + (1224 - 1004));
  CHECK(s["stall_cycles"]["l2_mshr_full"] == 0);
  CHECK(s["stall_cycles"]["dram_bandwidth"] == 0);
}

TEST_CASE("Memory hierarchy L2 MSHRs full delay the DRAM request", "[memory][hierarchy]") {
  MemoryConfig m = fast_channel_config();
  m.l1.mshrs = 8;
  m.l2.mshrs = 2;
  auto mem = make_memory(m, 2);
  CHECK(mem->read(0, 0 * kLine, 64, 0) == 112);
  CHECK(mem->read(1, 1 * kLine, 64, 0) == 112);
  // Reaches L2 at 2, waits for an L2 MSHR until 112, DRAM at 122.
  CHECK(mem->read(0, 2 * kLine, 64, 0) == 222);
  const auto s = mem->stats();
  CHECK(s["stall_cycles"]["l2_mshr_full"] == 110);
  CHECK(s["l2"]["mshr_stall_cycles"] == 110);
  CHECK(s["stall_cycles"]["l1_mshr_full"] == 0);
}

TEST_CASE("Memory hierarchy DRAM outstanding limit holds requests back", "[memory][hierarchy]") {
  MemoryConfig m = fast_channel_config();
  m.l1.mshrs = 8;
  m.l2.mshrs = 8;
  m.dram_max_outstanding = 2;
  auto mem = make_memory(m, 1);
  CHECK(mem->read(0, 0 * kLine, 64, 0) == 112);
  CHECK(mem->read(0, 1 * kLine, 64, 0) == 112);
  CHECK(mem->read(0, 2 * kLine, 64, 0) == 212);  // DRAM request at 12 starts at 112
  CHECK(mem->read(0, 3 * kLine, 64, 0) == 212);
  CHECK(mem->stats()["stall_cycles"]["dram_outstanding_full"] == 200);
}

TEST_CASE("Memory hierarchy back-to-back DRAM misses are spaced by the line transfer time", "[memory][hierarchy]") {
  MemoryConfig m = small_config();
  m.l1.mshrs = 8;
  m.l2.mshrs = 8;
  SECTION("16 bytes per cycle: 4 cycles per line") {
    auto mem = make_memory(m, 1);
    for (uint64_t i = 0; i < 6; ++i) CHECK(mem->read(0, i * kLine, 64, 0) == 112 + 4 * i);
    // An idle channel later: the unloaded latency again.
    CHECK(mem->read(0, 40 * kLine, 64, 1000) == 1112);
    const auto s = mem->stats();
    CHECK(s["stall_cycles"]["dram_bandwidth"] == 0 + 4 + 8 + 12 + 16 + 20);
    CHECK(s["dram"]["busy_cycles"].get<double>() == Approx(7 * 4.0));
    CHECK(s["span_cycles"] == 1112);
    CHECK(s["dram"]["bytes_per_cycle"].get<double>() == Approx(7 * 64.0 / 1112));
    CHECK(s["dram"]["bandwidth_use"].get<double>() == Approx(7 * 64.0 / 1112 / 16));
  }
  SECTION("24 bytes per cycle: 8 cycles per 3 lines") {
    m.dram_bytes_per_cycle = 24;
    auto mem = make_memory(m, 1);
    // Transfers end 8/3 cycles apart from cycle 12 + 8/3: ceil gives 15, 18, 20, 23, 26, 28.
    const uint64_t expected[] = {112, 115, 117, 120, 123, 125};
    for (uint64_t i = 0; i < 6; ++i) CHECK(mem->read(0, i * kLine, 64, 0) == expected[i]);
  }
}

TEST_CASE("Memory hierarchy matches explicit LRU lists on a random stream", "[memory][hierarchy]") {
  // Reads spaced further apart than the slowest miss: no contention, so each
  // read's latency names where its line was: 2 (L1), 12 (L2) or 112 (DRAM).
  const MemoryConfig m = small_config();
  const int cores = 2;
  auto mem = make_memory(m, cores);
  std::vector<ListLru> l1(cores, ListLru(2, 2));
  ListLru l2(4, 4);
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<uint64_t> hot(0, 9), wide(0, 63);
  std::uniform_int_distribution<uint32_t> offset(0, 63);
  int counts[3] = {0, 0, 0};
  uint64_t now = 0;
  for (int i = 0; i < 4000; ++i) {
    const int core = static_cast<int>(rng() % cores);
    const uint64_t line = (rng() % 4) ? hot(rng) : wide(rng);
    const uint32_t off = offset(rng);
    const uint32_t bytes = 1 + offset(rng) % (64 - off);  // stays inside the line
    uint64_t expected = 2;
    if (!l1[static_cast<size_t>(core)].access(line)) expected = l2.access(line) ? 12 : 112;
    counts[expected == 2 ? 0 : expected == 12 ? 1 : 2]++;
    INFO("read " << i << " core " << core << " line " << line);
    REQUIRE(mem->read(core, line * kLine + off, bytes, now) == now + expected);
    now += 150 + rng() % 3;
  }
  for (int c : counts) CHECK(c > 200);  // all three outcomes exercised
  const auto s = mem->stats();
  CHECK(s["l1"]["hits"] == counts[0]);
  CHECK(s["l2"]["hits"] == counts[1]);
  CHECK(s["dram"]["reads"] == counts[2]);
  CHECK(s["l1"]["merges"] == 0);
}

TEST_CASE("Memory hierarchy under load is deterministic and keeps its counters consistent", "[memory][hierarchy]") {
  MemoryConfig m = small_config();
  m.dram_max_outstanding = 3;
  auto run = [&](std::vector<uint64_t>& ready) {
    auto mem = make_memory(m, 4);
    std::mt19937_64 rng(99);
    uint64_t now = 0;
    for (int i = 0; i < 5000; ++i) {
      const int core = static_cast<int>(rng() % 4);
      const uint64_t addr = (rng() % 48) * 40 + (rng() % 2) * 4096;
      const uint64_t r = mem->read(core, addr, 40, now);
      REQUIRE(r >= now + 2);
      ready.push_back(r);
      now += rng() % 3;
    }
    return mem->stats();
  };
  std::vector<uint64_t> a, b;
  const auto sa = run(a), sb = run(b);
  CHECK(a == b);
  CHECK(sa == sb);
  const auto& l1 = sa["l1"];
  const auto& l2 = sa["l2"];
  CHECK(l1["accesses"] == sa["line_requests"]);
  CHECK(l1["accesses"].get<uint64_t>() ==
        l1["hits"].get<uint64_t>() + l1["misses"].get<uint64_t>() + l1["merges"].get<uint64_t>());
  CHECK(l2["accesses"] == l1["misses"]);
  CHECK(l2["accesses"].get<uint64_t>() ==
        l2["hits"].get<uint64_t>() + l2["misses"].get<uint64_t>() + l2["merges"].get<uint64_t>());
  CHECK(sa["dram"]["reads"] == l2["misses"]);
  CHECK(l1["merges"].get<uint64_t>() > 0);
  CHECK(l2["merges"].get<uint64_t>() > 0);
  CHECK(sa["stall_cycles"]["l1_mshr_full"].get<uint64_t>() > 0);
  CHECK(sa["stall_cycles"]["dram_bandwidth"].get<uint64_t>() > 0);
  CHECK(sa["stall_cycles"]["dram_outstanding_full"].get<uint64_t>() > 0);
}

TEST_CASE("Memory config errors name the field", "[memory][config]") {
  using Catch::Matchers::StartsWith;
  struct Case {
    void (*mutate)(MemoryConfig&);
    const char* prefix;
  };
  const Case cases[] = {
      {[](MemoryConfig& m) { m.l1.ways = 0; }, "memory.l1.ways: "},
      {[](MemoryConfig& m) { m.l1.ways = 512; }, "memory.l1.ways: "},
      {[](MemoryConfig& m) { m.l1.line_bytes = 48; }, "memory.l1.line_bytes: "},
      {[](MemoryConfig& m) { m.l1.size_bytes = 0; }, "memory.l1.size_bytes: "},
      {[](MemoryConfig& m) { m.l1.size_bytes = 1000; }, "memory.l1.size_bytes: "},
      {[](MemoryConfig& m) { m.l1.hit_latency = 0; }, "memory.l1.hit_latency: "},
      {[](MemoryConfig& m) { m.l1.mshrs = 0; }, "memory.l1.mshrs: "},
      {[](MemoryConfig& m) { m.l2.ways = 0; }, "memory.l2.ways: "},
      {[](MemoryConfig& m) { m.l2.mshrs = 0; }, "memory.l2.mshrs: "},
      {[](MemoryConfig& m) { m.l2.size_bytes = 3 * 8 * 64 + 1; }, "memory.l2.size_bytes: "},
      {[](MemoryConfig& m) { m.l2.line_bytes = 128; }, "memory.l2.line_bytes: "},
      {[](MemoryConfig& m) { m.dram_latency = 0; }, "memory.dram_latency: "},
      {[](MemoryConfig& m) { m.dram_bytes_per_cycle = 0; }, "memory.dram_bytes_per_cycle: "},
      {[](MemoryConfig& m) { m.dram_bytes_per_cycle = -1; }, "memory.dram_bytes_per_cycle: "},
      {[](MemoryConfig& m) { m.dram_max_outstanding = 0; }, "memory.dram_max_outstanding: "},
  };
  for (const Case& c : cases) {
    MemoryConfig m;
    c.mutate(m);
    REQUIRE_THROWS_AS(make_memory(m, 2), std::invalid_argument);
    REQUIRE_THROWS_WITH(make_memory(m, 2), StartsWith(c.prefix));
  }
  MemoryConfig too_many_ways;
  too_many_ways.l1.ways = 512;
  CHECK_THROWS_WITH(make_memory(too_many_ways, 2),
                    "memory.l1.ways: 512 ways of 64-byte lines do not fit in 16384 bytes");
  CHECK_THROWS_AS(make_memory(MemoryConfig{}, 0), std::invalid_argument);
  CHECK_NOTHROW(make_memory(MemoryConfig{}, 2));  // the defaults are valid
  CHECK_THROWS_AS(make_memory(MemoryConfig{}, 2)->read(2, 0, 64, 0), std::out_of_range);
  MemoryConfig three_sets;
  three_sets.l2 = {3 * 8 * 64, 8, 64, 14, 32};  // sets need not be a power of two
  CHECK_NOTHROW(make_memory(three_sets, 1));
}

TEST_CASE("Memory config ideal memory is unaffected by the hierarchy", "[memory][config]") {
  MemoryConfig m;
  m.ideal = true;
  m.ideal_latency = 7;
  m.l1.ways = 0;  // the caches are not checked when memory is ideal
  auto mem = make_memory(m, 3);
  CHECK(mem->read(2, 12345, 64, 10) == 17);
  CHECK(mem->read(0, 0, 40, 10) == 17);
  const auto s = mem->stats();
  CHECK(s["model"] == "ideal");
  CHECK(s["reads"] == 2);
  CHECK(s["bytes"] == 104);
}
