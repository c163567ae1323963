// Speed of the memory hierarchy model (hidden: run with
// `vbsim_tests "[memory-bench]"`). The stream imitates BVH traversal: every
// ray slot of every core walks root-to-leaf paths of a breadth-first laid out
// binary tree of 64-byte nodes (upper levels shared and hot, lower levels
// spread over 8 MiB, beyond the L2), then fetches a leaf's 40-byte triangles;
// the rays of a core share the upper part of their paths. Closed loop: a slot
// issues its next fetch 4 cycles after its data arrive, in time order. The
// calls that loop makes are recorded and replayed on a fresh hierarchy in a
// plain loop, which is what is timed (the answers must repeat exactly).
// Prints reads per wall second and the hit rates.
#include <catch2/catch.hpp>
#include <fmt/core.h>

#include <chrono>
#include <functional>
#include <queue>
#include <utility>
#include <random>
#include <vector>

#include "memory_rig.h"

using namespace vbsim::hw;
using vbsim::hw::test::make_memory;
using vbsim::hw::test::MemoryRig;

namespace {

struct Fetch {
  uint64_t addr;
  uint32_t bytes;
};

// One slot's fetches: `count` of them, root-to-leaf walks then triangles.
std::vector<Fetch> slot_stream(std::mt19937_64& rng, uint64_t core_paths_seed, size_t count) {
  const int depth = 17;
  const uint64_t node_bytes = 64, triangle_bytes = 40;
  const uint64_t triangles_base = (uint64_t{1} << depth) * node_bytes;
  std::mt19937_64 shared(core_paths_seed);  // the same sequence for every slot of a core
  std::vector<Fetch> s;
  while (s.size() < count) {
    const uint64_t coherent = shared(), own = rng();
    uint64_t node = 0;
    for (int level = 0; level < depth - 1; ++level) {
      s.push_back({node * node_bytes, static_cast<uint32_t>(node_bytes)});
      const uint64_t bits = level < 8 ? coherent : own;
      node = 2 * node + 1 + ((bits >> level) & 1);
    }
    const uint64_t first_triangle = (node - ((uint64_t{1} << (depth - 1)) - 1)) * 2;
    for (uint64_t k = 0; k < 2 + rng() % 3; ++k)
      s.push_back({triangles_base + (first_triangle + k) * triangle_bytes, static_cast<uint32_t>(triangle_bytes)});
  }
  s.resize(count);
  return s;
}

struct Call {
  int core;
  uint32_t bytes;
  uint64_t addr, now, ready;
};

// The calls of the closed loop over `mem`, in order, with their answers.
std::vector<Call> run_closed_loop(MemoryRig& mem, const std::vector<std::vector<Fetch>>& slots, int slots_per_core) {
  using Event = std::pair<uint64_t, uint32_t>;  // (cycle, slot)
  std::vector<Event> heap_storage;
  heap_storage.reserve(slots.size());
  std::priority_queue<Event, std::vector<Event>, std::greater<Event>> events(std::greater<Event>(),
                                                                             std::move(heap_storage));
  std::vector<size_t> next(slots.size(), 0);
  for (uint32_t i = 0; i < slots.size(); ++i) events.push({0, i});
  std::vector<Call> calls;
  while (!events.empty()) {
    const auto [now, slot] = events.top();
    events.pop();
    const Fetch f = slots[slot][next[slot]++];
    const int core = static_cast<int>(slot) / slots_per_core;
    const uint64_t ready = mem.read(core, f.addr, f.bytes, now);
    calls.push_back({core, f.bytes, f.addr, now, ready});
    if (next[slot] < slots[slot].size()) events.push({ready + 4, slot});
  }
  return calls;
}

}  // namespace

TEST_CASE("Memory hierarchy reads per second on a BVH-like stream", "[.bench][memory-bench]") {
  const int cores = 8, slots_per_core = 16;
  const size_t reads_per_slot = 30000;
  std::mt19937_64 rng(3);
  std::vector<std::vector<Fetch>> slots;
  for (int c = 0; c < cores; ++c)
    for (int s = 0; s < slots_per_core; ++s) slots.push_back(slot_stream(rng, 1000 + c, reads_per_slot));

  const std::vector<Call> calls = run_closed_loop(*make_memory(MemoryConfig{}, cores), slots, slots_per_core);

  auto mem = make_memory(MemoryConfig{}, cores);
  uint64_t mismatches = 0, latency = 0;
  const auto begin = std::chrono::steady_clock::now();
  for (const Call& c : calls) {
    const uint64_t ready = mem->read(c.core, c.addr, c.bytes, c.now);
    mismatches += ready != c.ready;
    latency += ready - c.now;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  const auto stats = mem->stats();
  const double reads = static_cast<double>(calls.size());
  fmt::print("memory hierarchy (default config, {} cores x {} slots): {} reads in {:.3f} s: {:.2f} M reads/s\n",
             cores, slots_per_core, calls.size(), seconds, reads / seconds / 1e6);
  fmt::print("simulated {} cycles; mean latency {:.1f} cycles; L1 hit rate {:.3f}, L2 hit rate {:.3f}, "
             "DRAM bandwidth use {:.3f}\n",
             calls.back().now, static_cast<double>(latency) / reads, stats["l1"]["hit_rate"].get<double>(),
             stats["l2"]["hit_rate"].get<double>(), stats["dram"]["bandwidth_use"].get<double>());
  fmt::print("stall cycles: {}\n", stats["stall_cycles"].dump());
  CHECK(mismatches == 0);
  CHECK(stats["reads"] == calls.size());
}
