// SamplePlan: which trace positions a sampled replay simulates in detail and
// which it measures (hw/sampling/sampling_config.h). Position p lies in unit
// p / unit; unit m is measured when m % interval == offset; p is simulated in
// detail when it lies in a measured unit or within the `warmup` positions
// before the start of the next measured unit. Pure arithmetic, no state.
#pragma once
#include <cstdint>

#include "hw/sampling/sampling_config.h"

namespace vbsim::hw {

class SamplePlan {
 public:
  explicit SamplePlan(const SamplingConfig& c)
      : unit_(c.unit), interval_(c.interval), offset_(c.measured_offset()), warmup_(c.warmup) {}

  uint64_t unit_of(uint64_t pos) const { return pos / unit_; }
  bool measured_unit(uint64_t m) const { return m % interval_ == offset_; }
  /// The first position of the first measured unit whose start is at or after
  /// the start of pos's unit.
  uint64_t next_measured_start(uint64_t pos) const {
    const uint64_t m = unit_of(pos);
    const uint64_t r = m % interval_;
    const uint64_t ahead = r <= offset_ ? offset_ - r : interval_ - r + offset_;
    return (m + ahead) * unit_;
  }
  /// Simulated in detail (a measured unit's ray, or one of its warm-up rays).
  bool detailed(uint64_t pos) const { return pos + warmup_ >= next_measured_start(pos); }
  uint64_t unit() const { return unit_; }

 private:
  uint64_t unit_, interval_, offset_, warmup_;
};

}  // namespace vbsim::hw
