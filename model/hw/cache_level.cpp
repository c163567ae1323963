#include "hw/cache_level.h"

namespace vbsim::hw {

CacheLevel::CacheLevel(const CacheConfig& config)
    : tags_(config.size_bytes / (config.ways * config.line_bytes), config.ways),
      hit_latency_(config.hit_latency),
      flight_line_(config.mshrs, LruCache::kNoLine),
      fill_(config.mshrs, 0),
      order_(config.mshrs, 0) {
  due_.reserve(config.mshrs);
}

void CacheLevel::retire_slow(uint64_t horizon) {
  // One pass: the fills due by `horizon` (usually one) and the earliest fill after it.
  const uint32_t n = static_cast<uint32_t>(flight_line_.size());
  uint32_t due = 0, last_due = 0;
  uint64_t later = ~uint64_t{0};
  for (uint32_t i = 0; i < n; ++i) {
    if (flight_line_[i] == LruCache::kNoLine) continue;
    if (fill_[i] <= horizon) {
      ++due;
      last_due = i;
    } else if (fill_[i] < later) {
      later = fill_[i];
    }
  }
  next_fill_ = later;
  if (due == 1) {
    tags_.install(flight_line_[last_due]);
    flight_line_[last_due] = LruCache::kNoLine;
    return;
  }
  // Several: installed in (fill cycle, claim order) order.
  due_.clear();
  for (uint32_t i = 0; i < n; ++i)
    if (flight_line_[i] != LruCache::kNoLine && fill_[i] <= horizon) {
      size_t at = due_.size();
      due_.push_back(i);
      for (; at > 0; --at) {
        const uint32_t prev = due_[at - 1];
        if (fill_[prev] < fill_[i] || (fill_[prev] == fill_[i] && order_[prev] < order_[i])) break;
        due_[at] = prev;
      }
      due_[at] = i;
    }
  for (const uint32_t i : due_) {
    tags_.install(flight_line_[i]);
    flight_line_[i] = LruCache::kNoLine;
  }
}

}  // namespace vbsim::hw
