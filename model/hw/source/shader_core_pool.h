// ShaderCorePool: the shader cores that run the software methods'
// emission-time arithmetic (hw.shader.cores), where a GPU runs it: on the SIMD
// cores that shade a hit and write its children, before they call the
// ray-emission API. The sign bit stays on the emission path (the ray source's
// lanes), as the patent has it.
//
// Timing: `cores` cores of `simd_lanes` lanes, each lane `ops_per_lane_cycle`
// operations a cycle. A ray's n operations run on one lane, in order: its
// result is there ceil(n / ops_per_lane_cycle) + pipeline_latency cycles after
// it starts (its latency). Throughput is shared: a core issues at most
// simd_lanes x ops_per_lane_cycle operations a cycle, so a ray takes
// n / (simd_lanes x ops_per_lane_cycle) of a core's issue cycles (kept exactly,
// in units of 1 / (simd_lanes x ops_per_lane_cycle) cycle); a ray starts on the
// core that can start it first (the lowest numbered among equals), at or after
// the cycle it is ready. Requests come in time order (the ray source asks when
// a ray's dependencies are resolved) and are served in that order.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "hw/hw_config.h"

namespace vbsim::hw {

class ShaderCorePool {
 public:
  /// `c.cores` >= 1 (the configuration is validated).
  explicit ShaderCorePool(const ShaderConfig& c)
      : ops_per_lane_(c.ops_per_lane_cycle),
        latency_(c.pipeline_latency),
        per_cycle_(uint64_t{c.simd_lanes} * c.ops_per_lane_cycle),
        free_(c.cores, 0) {}

  /// A ray's `ops` operations, ready at cycle `ready`: the cycle its result is there.
  uint64_t run(uint64_t ready, uint32_t ops) {
    size_t best = 0;
    for (size_t c = 1; c < free_.size(); ++c)
      if (free_[c] < free_[best]) best = c;
    // free_ in units of 1 / per_cycle_ cycle: the core's issue slots taken up to there.
    const uint64_t ready_units = ready * per_cycle_;
    const uint64_t start_units = std::max(ready_units, free_[best]);
    free_[best] = start_units + ops;
    const uint64_t start = (start_units + per_cycle_ - 1) / per_cycle_;  // its first operation's cycle
    ++rays_;
    ops_ += ops;
    wait_cycles_ += start - ready;
    lane_cycles_ += (ops + ops_per_lane_ - 1) / ops_per_lane_;
    return start + (ops + ops_per_lane_ - 1) / ops_per_lane_ + latency_;
  }

  uint64_t rays() const { return rays_; }
  uint64_t ops() const { return ops_; }
  /// Summed over rays: cycles from ready to the first operation (throughput waits).
  uint64_t wait_cycles() const { return wait_cycles_; }
  /// Summed over rays: the cycles a lane spent on each (ceil(n / ops_per_lane_cycle)).
  uint64_t lane_cycles() const { return lane_cycles_; }
  /// The operations the pool could issue in `cycles` cycles.
  uint64_t capacity(uint64_t cycles) const { return cycles * per_cycle_ * free_.size(); }

 private:
  uint32_t ops_per_lane_, latency_;
  uint64_t per_cycle_;          ///< operations one core issues a cycle
  std::vector<uint64_t> free_;  ///< per core: its issue slots taken up to here (1 / per_cycle_ cycle units)
  uint64_t rays_ = 0, ops_ = 0, wait_cycles_ = 0, lane_cycles_ = 0;
};

}  // namespace vbsim::hw
