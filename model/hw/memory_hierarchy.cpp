#include "hw/memory_hierarchy.h"

#include <stdexcept>

namespace vbsim::hw {

namespace {

uint32_t log2_of(uint32_t power_of_two) {
  uint32_t s = 0;
  while ((uint32_t{1} << s) < power_of_two) ++s;
  return s;
}

double ratio(uint64_t part, uint64_t whole) {
  return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

nlohmann::json level_json(const LevelCounters& c) {
  return {{"accesses", c.accesses},
          {"hits", c.hits},
          {"misses", c.misses},
          {"merges", c.merges},
          {"hit_rate", ratio(c.hits, c.accesses)},
          {"mshr_stall_cycles", c.mshr_stall_cycles}};
}

}  // namespace

MemoryHierarchy::MemoryHierarchy(const MemoryConfig& config, int cores)
    : config_(config),
      shape_(config.l1.ways == 4 && config.l2.ways == 8    ? Shape::L1x4L2x8
             : config.l1.ways == 4 && config.l2.ways == 16 ? Shape::L1x4L2x16
                                                           : Shape::Any),
      line_shift_(log2_of(config.l1.line_bytes)),
      l1_(static_cast<size_t>(cores), CacheLevel(config.l1)),
      l2_(config.l2),
      dram_(config.dram_latency, config.dram_bytes_per_cycle, config.l2.line_bytes,
            config.dram_max_outstanding) {}

// Inlined into both of read()'s calls (the first line's, the loop's).
template <uint32_t L1Ways, uint32_t L2Ways>
__attribute__((always_inline)) inline uint64_t MemoryHierarchy::read_line(CacheLevel& l1, uint64_t line,
                                                                         uint64_t now) {
  const CacheLevel::Access miss = l1.access<L1Ways>(line, now);
  if (miss.outcome != CacheLevel::Outcome::Miss) return miss.ready;
  const uint64_t fill = read_l2<L2Ways>(line, miss.start + l1.hit_latency());
  l1.fill<L1Ways>(line, fill, miss.start);
  return fill;
}

template <uint32_t L2Ways>
__attribute__((always_inline)) inline uint64_t MemoryHierarchy::read_l2(uint64_t line, uint64_t t) {
  const CacheLevel::Access miss = l2_.access<L2Ways>(line, t);
  if (miss.outcome != CacheLevel::Outcome::Miss) return miss.ready;
  const uint64_t fill = dram_.read_line(miss.start + l2_.hit_latency());
  l2_.fill<L2Ways>(line, fill, miss.start);
  return fill;
}

uint64_t MemoryHierarchy::read(int core, uint64_t addr, uint32_t bytes, uint64_t now) {
  switch (shape_) {  // the presets' associativities: their loops unrolled, no switch per lookup
    case Shape::L1x4L2x8: return read_shaped<4, 8>(core, addr, bytes, now);
    case Shape::L1x4L2x16: return read_shaped<4, 16>(core, addr, bytes, now);
    default: return read_shaped<0, 0>(core, addr, bytes, now);
  }
}

template <uint32_t L1Ways, uint32_t L2Ways>
uint64_t MemoryHierarchy::read_shaped(int core, uint64_t addr, uint32_t bytes, uint64_t now) {
  if (core < 0 || static_cast<size_t>(core) >= l1_.size())
    throw std::out_of_range("memory: read by core " + std::to_string(core) + " of " +
                            std::to_string(l1_.size()));
  CacheLevel& l1 = l1_[static_cast<size_t>(core)];
  const uint64_t first = addr >> line_shift_;
  const uint64_t last = (addr + (bytes ? bytes - 1 : 0)) >> line_shift_;
  uint64_t ready = read_line<L1Ways, L2Ways>(l1, first, now);  // a node read: its only line
  for (uint64_t line = first + 1; line <= last; ++line) {
    const uint64_t r = read_line<L1Ways, L2Ways>(l1, line, now);
    if (r > ready) ready = r;
  }
  if (reads_ == 0) first_now_ = now;
  if (ready > last_ready_) last_ready_ = ready;
  ++reads_;
  bytes_ += bytes;
  return ready;
}

nlohmann::json MemoryHierarchy::stats() const {
  LevelCounters l1_sum;
  nlohmann::json per_core = nlohmann::json::array();
  for (const CacheLevel& l1 : l1_) {
    const LevelCounters c = l1.counters();
    l1_sum.accesses += c.accesses;
    l1_sum.hits += c.hits;
    l1_sum.misses += c.misses;
    l1_sum.merges += c.merges;
    l1_sum.mshr_stall_cycles += c.mshr_stall_cycles;
    per_core.push_back(level_json(c));
  }
  nlohmann::json l1 = level_json(l1_sum);
  l1["per_core"] = std::move(per_core);

  const DramCounters& d = dram_.counters();
  const uint64_t span = reads_ ? last_ready_ - first_now_ : 0;
  const double bytes_per_cycle = span ? static_cast<double>(d.bytes) / static_cast<double>(span) : 0.0;
  return {
      {"model", "hierarchy"},
      {"reads", reads_},
      {"bytes", bytes_},
      {"line_requests", l1_sum.accesses},  // every line a read spans is one L1 access
      {"span_cycles", span},
      {"l1", std::move(l1)},
      {"l2", level_json(l2_.counters())},
      {"dram",
       {{"reads", d.reads},
        {"bytes", d.bytes},
        {"busy_cycles", dram_.busy_cycles()},
        {"bytes_per_cycle", bytes_per_cycle},
        {"bandwidth_use", bytes_per_cycle / config_.dram_bytes_per_cycle}}},
      {"stall_cycles",
       {{"l1_mshr_full", l1_sum.mshr_stall_cycles},
        {"l2_mshr_full", l2_.counters().mshr_stall_cycles},
        {"dram_outstanding_full", d.outstanding_stall_cycles},
        {"dram_bandwidth", d.bandwidth_stall_cycles}}},
  };
}

}  // namespace vbsim::hw
