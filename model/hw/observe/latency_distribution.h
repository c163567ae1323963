// LatencyDistribution: the exact distribution of per-ray latencies (cycles) of
// a run: a count for every latency value up to the longest seen, so that its
// percentiles are exact and its histogram's buckets can be chosen once the
// run's range is known (powers of two up to the longest latency: every ray
// falls in a bucket, none in an open-ended overflow bucket).
//
// A percentile p is the nearest-rank one: the smallest latency L such that at
// least ceil(p / 100 * rays) rays took L cycles or fewer (p100: the longest).
#pragma once
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

namespace vbsim::hw {

class LatencyDistribution {
 public:
  /// One ray of `latency` cycles (amortised O(1): the counts grow only with a new longest latency).
  void add(uint64_t latency) {
    if (__builtin_expect(latency >= counts_.size(), 0)) grow(latency);
    ++counts_[latency];
    ++rays_;
    sum_ += latency;
  }
  uint64_t rays() const { return rays_; }
  uint64_t sum() const { return sum_; }
  uint64_t min() const;
  uint64_t max() const;
  double mean() const { return rays_ ? static_cast<double>(sum_) / static_cast<double>(rays_) : 0.0; }
  /// The nearest-rank percentile `p` (0 < p <= 100); 0 without rays.
  uint64_t percentile(double p) const;

  /// Adds `o`'s rays.
  void merge(const LatencyDistribution& o);
  /// Takes away `earlier`'s rays (a snapshot of this distribution taken before).
  void subtract(const LatencyDistribution& earlier);

  /// {"rays", "mean", "min", "p50", "p90", "p95", "p99", "max"}.
  nlohmann::json summary_json() const;
  /// Buckets [0, 1), [1, 2), [2, 4), ... [2^k, 2^(k+1)) up to the one holding
  /// the longest latency: [{"from", "to", "rays"}, ...] (to exclusive).
  nlohmann::json log2_histogram_json() const;

 private:
  __attribute__((noinline)) void grow(uint64_t latency);
  std::vector<uint64_t> counts_;  ///< by latency in cycles
  uint64_t rays_ = 0, sum_ = 0;
};

}  // namespace vbsim::hw
