// Statistics over parts of a run: a warm-up excluded from the measured
// figures, and a time series of intervals of K cycles.
//
// Both are differences of StatsSample, the chip's cumulative counters taken
// when every event before a cycle is handled and none of that cycle is
// (EngineParts::on_sample): an interval [a, b) is sample(b) - sample(a), the
// measured part of a run is sample(end) - sample(warm-up's end), where end is
// the cycle after the last ray finished. Each counter falls in the interval of
// the cycle the model counts it at: a ray at the cycle it finishes, a cache
// lookup at the cycle it is made, a DRAM read when it is sent, a unit
// operation when it is scheduled (up to a few cycles before it issues), so
// the intervals' sums are the run's totals.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "hw/hw_config.h"
#include "hw/memory/cache_level.h"
#include "hw/observe/latency_distribution.h"

namespace vbsim {
class AtomicOutputFile;
}

namespace vbsim::hw {

/// The chip's cumulative counters at the start of cycle `cycle`.
struct StatsSample {
  uint64_t cycle = 0;
  uint64_t rays = 0, latency_sum = 0;
  std::array<uint64_t, 3> unit_ops{};          ///< box, triangle, avoidance
  std::array<bool, 3> unit_replaced{};         ///< a replacement's pipelines are its own: no busy fraction
  uint64_t node_fetches = 0, leaf_fetches = 0;
  LevelCounters l1, l2;                        ///< l1: all cores' summed
  bool caches = false;                         ///< a cache hierarchy (else an ideal memory)
  uint64_t dram_reads = 0, dram_bytes = 0;
  /// Miss latency parts (RunStatistics::miss_latency_json): per level, summed
  /// over its misses whose data have come, the cycles from leaving the
  /// level's MSHR to the data (the L2's lookup latency included), and those misses.
  uint64_t l1_miss_service_cycles = 0, l1_misses_filled = 0;
  uint64_t l2_miss_service_cycles = 0, l2_misses_filled = 0;
  /// Only in the warm-up's sample: the latencies of the rays finished by then, by kind.
  std::array<LatencyDistribution, kRayKindCount> latency_by_kind;
};

/// The warm-up and interval options of one run.
struct StatisticsOptions {
  std::string interval_path;   ///< JSON lines of intervals (empty: none)
  uint64_t interval_cycles = 0;
  uint64_t warmup_rays = 0, warmup_cycles = 0;  ///< at most one non-zero (HwConfig's sim.warmup_*)
  bool warmup() const { return warmup_rays || warmup_cycles; }
};

class RunStatistics {
 public:
  /// Opens the interval file's temporary (OutputError when it cannot be created).
  RunStatistics(const HwConfig& config, StatisticsOptions options);
  ~RunStatistics();

  const StatisticsOptions& options() const { return options_; }
  /// A sample (see EngineParts::on_sample); writes the interval that ends at it.
  void sample(const StatsSample& s, bool interval, bool warmup);
  /// The run's end (the cycle after the last ray): the last interval, the file
  /// named. Throws std::runtime_error when the warm-up excluded every ray.
  void finish(const StatsSample& end);

  /// `hw.warmup`: what the warm-up excluded (null without one).
  nlohmann::json warmup_json() const;
  /// `hw.measured`: the figures after the warm-up (null without one).
  nlohmann::json measured_json() const { return measured_; }

  /// One interval's (or part of a run's) figures: b - a.
  static nlohmann::json difference_json(const StatsSample& a, const StatsSample& b, const HwConfig& config);
  /// {"l1": {...}, "l2": {...}}: per level, its misses and their mean latency
  /// from the lookup to the line's data (MSHR wait included); null for an ideal memory.
  static nlohmann::json miss_latency_json(const StatsSample& a, const StatsSample& b);

 private:
  const HwConfig& config_;
  StatisticsOptions options_;
  std::unique_ptr<AtomicOutputFile> file_;
  StatsSample last_;                      ///< the interval file's last row's end
  std::unique_ptr<StatsSample> warm_;     ///< the warm-up's sample, once taken
  nlohmann::json measured_;
  uint64_t rows_ = 0;
};

/// The human table's lines: latency percentiles, miss latency per level and,
/// with a warm-up, the figures after it (`statistics` may be null).
std::string run_statistics_lines(const StatsSample& end, const RunStatistics* statistics);

/// `hw.latency_distribution`: overall and per-kind percentiles and a histogram of log2 buckets.
nlohmann::json latency_distribution_json(const std::array<LatencyDistribution, kRayKindCount>& by_kind);

}  // namespace vbsim::hw
