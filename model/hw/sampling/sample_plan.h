// SamplePlan: which trace positions a sampled replay simulates in detail and
// which it measures (hw/sampling/sampling_config.h). Three strata:
//   head  positions [0, head): simulated in detail and measured whole (the
//         run's start from empty caches and an empty machine);
//   tail  positions [total - tail, total), when the trace's length is known:
//         in detail and measured whole (the run's end, its drain);
//   body  the rest, cut into units of `unit` rays from the head's end (the
//         last one cut short by the tail); body unit m is measured when
//         m % interval == offset.
// A body position is simulated in detail when it lies in a measured unit or
// within the `warmup` positions before the next measured unit or the tail.
// Pure arithmetic, no state.
#pragma once
#include <algorithm>
#include <cstdint>

#include "hw/sampling/sampling_config.h"

namespace vbsim::hw {

class SamplePlan {
 public:
  static constexpr uint64_t kNever = ~uint64_t{0} >> 1;

  explicit SamplePlan(const SamplingConfig& c)
      : unit_(c.unit), interval_(c.interval), offset_(c.measured_offset()), warmup_(c.warmup),
        head_(c.total ? std::min(c.head, c.total) : c.head),
        tail_start_(c.total && c.tail ? std::max(head_, c.total - std::min(c.tail, c.total)) : kNever) {}

  bool in_head(uint64_t pos) const { return pos < head_; }
  bool in_tail(uint64_t pos) const { return pos >= tail_start_; }
  uint64_t head() const { return head_; }
  uint64_t tail_start() const { return tail_start_; }
  /// Body positions only (head <= pos < tail_start).
  uint64_t body_unit(uint64_t pos) const { return (pos - head_) / unit_; }
  uint64_t unit_start(uint64_t m) const { return head_ + m * unit_; }
  /// Rays of body unit m (the last one cut short by the tail).
  uint64_t unit_rays(uint64_t m) const { return std::min(unit_start(m) + unit_, tail_start_) - unit_start(m); }
  bool measured_unit(uint64_t m) const { return m % interval_ == offset_; }
  /// A body position that starts a measured unit.
  bool starts_measured_unit(uint64_t pos) const {
    return pos >= head_ && pos < tail_start_ && (pos - head_) % unit_ == 0 && measured_unit(body_unit(pos));
  }
  /// The first position of the next measured stretch at or after the start of
  /// pos's body unit: a measured unit's start, or the tail's.
  uint64_t next_measured_start(uint64_t pos) const {
    const uint64_t m = body_unit(pos);
    const uint64_t r = m % interval_;
    const uint64_t ahead = r <= offset_ ? offset_ - r : interval_ - r + offset_;
    return std::min(unit_start(m + ahead), tail_start_);
  }
  /// Simulated in detail: the head, the tail, a measured unit's ray or one of the warm-up rays before them.
  bool detailed(uint64_t pos) const {
    return in_head(pos) || in_tail(pos) || pos + warmup_ >= next_measured_start(pos);
  }
  uint64_t unit() const { return unit_; }

 private:
  uint64_t unit_, interval_, offset_, warmup_, head_, tail_start_;
};

}  // namespace vbsim::hw
