#include "hw/observe/latency_distribution.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vbsim::hw {

void LatencyDistribution::grow(uint64_t latency) {
  if (latency > (uint64_t{1} << 32))
    throw std::runtime_error("hw: a ray latency of more than 2^32 cycles (the latency distribution's limit)");
  counts_.resize(std::max<uint64_t>(latency + 1, counts_.size() * 2), 0);
}

uint64_t LatencyDistribution::min() const {
  for (uint64_t l = 0; l < counts_.size(); ++l)
    if (counts_[l]) return l;
  return 0;
}

uint64_t LatencyDistribution::max() const {
  for (uint64_t l = counts_.size(); l-- > 0;)
    if (counts_[l]) return l;
  return 0;
}

uint64_t LatencyDistribution::percentile(double p) const {
  if (rays_ == 0) return 0;
  // The rank: ceil(p / 100 * rays), at least 1; computed in integers for p with
  // up to 4 decimals so that p50 of 10 rays is rank 5 exactly.
  const uint64_t scaled = static_cast<uint64_t>(std::llround(p * 10000.0));  // p in 1e-4 percent
  const uint64_t rank = std::max<uint64_t>(1, (scaled * rays_ + 1000000 - 1) / 1000000);
  uint64_t seen = 0;
  for (uint64_t l = 0; l < counts_.size(); ++l) {
    seen += counts_[l];
    if (seen >= rank) return l;
  }
  return max();
}

void LatencyDistribution::merge(const LatencyDistribution& o) {
  if (o.counts_.size() > counts_.size()) counts_.resize(o.counts_.size(), 0);
  for (size_t l = 0; l < o.counts_.size(); ++l) counts_[l] += o.counts_[l];
  rays_ += o.rays_;
  sum_ += o.sum_;
}

void LatencyDistribution::subtract(const LatencyDistribution& earlier) {
  if (earlier.counts_.size() > counts_.size()) throw std::logic_error("LatencyDistribution: not an earlier snapshot");
  for (size_t l = 0; l < earlier.counts_.size(); ++l) {
    if (earlier.counts_[l] > counts_[l]) throw std::logic_error("LatencyDistribution: not an earlier snapshot");
    counts_[l] -= earlier.counts_[l];
  }
  rays_ -= earlier.rays_;
  sum_ -= earlier.sum_;
}

nlohmann::json LatencyDistribution::summary_json() const {
  return {{"rays", rays_},           {"mean", mean()},           {"min", min()},
          {"p50", percentile(50)},   {"p90", percentile(90)},   {"p95", percentile(95)},
          {"p99", percentile(99)},   {"max", max()}};
}

nlohmann::json LatencyDistribution::log2_histogram_json() const {
  nlohmann::json out = nlohmann::json::array();
  if (rays_ == 0) return out;
  const uint64_t longest = max();
  for (uint64_t from = 0, to = 1;; from = to, to *= 2) {
    uint64_t n = 0;
    for (uint64_t l = from; l < to && l < counts_.size(); ++l) n += counts_[l];
    out.push_back({{"from", from}, {"to", to}, {"rays", n}});
    if (longest < to) break;
  }
  return out;
}

}  // namespace vbsim::hw
