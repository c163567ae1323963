#include "hw/cache_level.h"

namespace vbsim::hw {

CacheLevel::CacheLevel(const CacheConfig& config)
    : tags_(config.size_bytes / (config.ways * config.line_bytes), config.ways),
      hit_latency_(config.hit_latency),
      mshrs_(config.mshrs) {}

void CacheLevel::retire_slow(uint64_t horizon) {
  for (;;) {
    Mshr* first = nullptr;
    for (Mshr& m : mshrs_)
      if (m.in_flight && m.fill <= horizon &&
          (!first || m.fill < first->fill || (m.fill == first->fill && m.order < first->order)))
        first = &m;
    if (!first) break;
    tags_.install(first->line);
    first->in_flight = false;
  }
  next_fill_ = ~uint64_t{0};
  for (const Mshr& m : mshrs_)
    if (m.in_flight && m.fill < next_fill_) next_fill_ = m.fill;
}

CacheLevel::Lookup CacheLevel::lookup(uint64_t line, uint64_t t) {
  ++counters_.accesses;
  for (const Mshr& m : mshrs_)
    if (m.in_flight && m.line == line) {
      if (t < m.fill) {
        ++counters_.merges;
        return {Outcome::Merge, m.fill};
      }
      ++counters_.hits;  // filled but not yet installed: present all the same
      return {Outcome::Hit, t + hit_latency_};
    }
  if (tags_.touch(line)) {
    ++counters_.hits;
    return {Outcome::Hit, t + hit_latency_};
  }
  ++counters_.misses;
  return {Outcome::Miss, 0};
}

CacheLevel::MissStart CacheLevel::start_miss(uint64_t t) {
  uint32_t best = 0;
  for (uint32_t i = 1; i < mshrs_.size(); ++i)
    if (mshrs_[i].fill < mshrs_[best].fill) best = i;
  const uint64_t start = mshrs_[best].fill > t ? mshrs_[best].fill : t;
  counters_.mshr_stall_cycles += start - t;
  return {best, start};
}

void CacheLevel::hold(uint32_t mshr, uint64_t line, uint64_t fill) {
  Mshr& m = mshrs_[mshr];
  if (m.in_flight) tags_.install(m.line);  // filled before this miss started: present now
  m.line = line;
  m.fill = fill;
  m.order = ++claims_;
  m.in_flight = true;
  if (fill < next_fill_) next_fill_ = fill;
}

}  // namespace vbsim::hw
