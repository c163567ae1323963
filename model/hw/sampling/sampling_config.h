// SamplingConfig: the parameters of a sampled cycle-level replay
// (hw/sampling/sampled_feed.h; docs/sampling.md), SMARTS-style systematic
// sampling: the trace is cut into measurement units of `unit` rays; one unit
// in every `interval` is measured (the unit `offset` of each interval), after
// `warmup` rays simulated in detail and not measured; every other ray is
// fast-forwarded: answered by the functional datapath while its memory reads
// warm the caches' tags. The trace's first `head` and last `tail` rays are
// simulated in detail and measured whole (hw/sampling/sample_plan.h).
#pragma once
#include <cstdint>

#include <nlohmann/json.hpp>

namespace vbsim::hw {

struct SamplingConfig {
  uint64_t unit = 1000;      ///< rays per measurement unit (>= 1)
  uint64_t interval = 10;    ///< one unit measured every `interval` units (>= 1; 1: every unit)
  uint64_t warmup = 1000;    ///< rays simulated in detail, unmeasured, before each measured unit
  uint64_t head = 10000;     ///< the trace's first rays, simulated in detail and measured whole
  uint64_t tail = 2000;      ///< its last rays, the same (only when `total` is known)
  uint64_t total = 0;        ///< the trace's rays when known beforehand (0: unknown, no tail stratum)
  int64_t offset = -1;       ///< the measured unit within each interval, 0 .. interval - 1 (-1: interval / 2)
  double confidence = 0.95;  ///< of the intervals, in (0, 1)
  /// Stopping rule: once the cycles' interval half-width relative to the
  /// estimate is at most this (and at least `min_units` units are measured),
  /// measuring stops and the rest of the trace is fast-forwarded. 0: none.
  double error = 0;
  uint64_t min_units = 10;   ///< units measured before the stopping rule may act (>= 2)
  /// Fast-forwarded rays warm the caches (off only to show what warming is worth).
  bool warm = true;

  uint64_t measured_offset() const { return offset < 0 ? interval / 2 : static_cast<uint64_t>(offset); }
};

/// Throws std::invalid_argument naming the option ("--sample-unit: must be >= 1").
void check_sampling_config(const SamplingConfig& c);
/// The parameters as hw.sampling.parameters writes them.
nlohmann::json sampling_config_json(const SamplingConfig& c);

}  // namespace vbsim::hw
