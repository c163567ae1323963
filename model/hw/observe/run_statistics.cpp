#include "hw/observe/run_statistics.h"

#include <fmt/format.h>

#include <stdexcept>

#include "io/atomic_output_file.h"

namespace vbsim::hw {

namespace {

double per(double num, double den) { return den > 0 ? num / den : 0.0; }

nlohmann::json level_difference(const LevelCounters& a, const LevelCounters& b) {
  const uint64_t accesses = (b.hits + b.misses + b.merges) - (a.hits + a.misses + a.merges);
  return {{"accesses", accesses},
          {"hits", b.hits - a.hits},
          {"merges", b.merges - a.merges},
          {"misses", b.misses - a.misses},
          {"hit_rate", per(static_cast<double>(b.hits - a.hits), static_cast<double>(accesses))}};
}

nlohmann::json miss_level(uint64_t misses, uint64_t filled, uint64_t service_cycles, uint64_t mshr_cycles) {
  // From the lookup to the data: the MSHR wait, then the service (from the miss's leaving).
  const double total = static_cast<double>(service_cycles) + static_cast<double>(mshr_cycles);
  return {{"misses", misses}, {"misses_filled", filled}, {"mean_cycles", per(total, static_cast<double>(filled))}};
}

}  // namespace

RunStatistics::RunStatistics(const HwConfig& config, StatisticsOptions options)
    : config_(config), options_(std::move(options)) {
  if (options_.warmup_rays && options_.warmup_cycles)
    throw std::invalid_argument("hw: a warm-up by rays and by cycles at once (set one of sim.warmup_rays, sim.warmup_cycles)");
  if (!options_.interval_path.empty()) {
    if (options_.interval_cycles == 0) throw std::invalid_argument("hw: interval statistics need an interval of at least 1 cycle");
    file_ = std::make_unique<AtomicOutputFile>(options_.interval_path);
  }
}

RunStatistics::~RunStatistics() = default;

void RunStatistics::sample(const StatsSample& s, bool interval, bool warmup) {
  if (warmup) warm_ = std::make_unique<StatsSample>(s);
  if (interval && file_) {
    nlohmann::json row = difference_json(last_, s, config_);
    file_->stream() << row.dump() << "\n";
    file_->check();
    last_ = s;
    last_.latency_by_kind = {};
    ++rows_;
  }
}

void RunStatistics::finish(const StatsSample& end) {
  if (file_) {
    if (end.cycle > last_.cycle || rows_ == 0) file_->stream() << difference_json(last_, end, config_).dump() << "\n";
    file_->commit();
  }
  if (!options_.warmup()) return;
  const std::string what = options_.warmup_rays ? fmt::format("sim.warmup_rays = {}", options_.warmup_rays)
                                                : fmt::format("sim.warmup_cycles = {}", options_.warmup_cycles);
  if (!warm_ || warm_->cycle >= end.cycle || warm_->rays >= end.rays)
    throw std::runtime_error(fmt::format(
        "hw: the warm-up ({}) excludes every ray of the run ({} rays, the last finished at cycle {}): no figures "
        "are left to measure",
        what, end.rays, end.cycle == 0 ? 0 : end.cycle - 1));
  measured_ = difference_json(*warm_, end, config_);
  std::array<LatencyDistribution, kRayKindCount> after = end.latency_by_kind;
  for (int k = 0; k < kRayKindCount; ++k) after[k].subtract(warm_->latency_by_kind[k]);
  measured_["latency_distribution"] = latency_distribution_json(after);
  measured_["miss_latency"] = miss_latency_json(*warm_, end);
}

nlohmann::json RunStatistics::warmup_json() const {
  if (!options_.warmup() || !warm_) return nullptr;
  return {{"by", options_.warmup_rays ? "rays" : "cycles"},
          {"warmup_rays", options_.warmup_rays},
          {"warmup_cycles", options_.warmup_cycles},
          {"measured_from_cycle", warm_->cycle},
          {"excluded_cycles", warm_->cycle},
          {"excluded_rays", warm_->rays}};
}

nlohmann::json RunStatistics::difference_json(const StatsSample& a, const StatsSample& b, const HwConfig& cfg) {
  const uint64_t cycles = b.cycle - a.cycle, rays = b.rays - a.rays;
  const UnitConfig* units[3] = {&cfg.box, &cfg.triangle, &cfg.avoidance};
  static const char* kNames[3] = {"box", "triangle", "avoidance"};
  nlohmann::json u = nlohmann::json::object();
  for (int i = 0; i < 3; ++i) {
    const uint64_t ops = b.unit_ops[i] - a.unit_ops[i];
    // The share of the issue slots of every pipeline of this kind that were used.
    const double busy = per(static_cast<double>(ops) * units[i]->issue_interval,
                            static_cast<double>(cycles) * units[i]->count * unit_groups(*units[i], cfg.cores));
    u[kNames[i]] = {{"ops", ops}, {"busy", b.unit_replaced[i] ? nlohmann::json(nullptr) : nlohmann::json(busy)}};
  }
  nlohmann::json j = {{"start", a.cycle},
                      {"end", b.cycle},
                      {"cycles", cycles},
                      {"rays", rays},
                      {"rays_per_cycle", per(static_cast<double>(rays), static_cast<double>(cycles))},
                      {"latency_mean", per(static_cast<double>(b.latency_sum - a.latency_sum), static_cast<double>(rays))},
                      {"units", std::move(u)},
                      {"node_fetches", b.node_fetches - a.node_fetches},
                      {"leaf_fetches", b.leaf_fetches - a.leaf_fetches}};
  if (b.caches) {
    j["l1"] = level_difference(a.l1, b.l1);
    j["l2"] = level_difference(a.l2, b.l2);
    j["dram"] = {{"reads", b.dram_reads - a.dram_reads},
                 {"bytes", b.dram_bytes - a.dram_bytes},
                 {"bytes_per_cycle", per(static_cast<double>(b.dram_bytes - a.dram_bytes), static_cast<double>(cycles))}};
  }
  return j;
}

nlohmann::json RunStatistics::miss_latency_json(const StatsSample& a, const StatsSample& b) {
  if (!b.caches) return nullptr;
  return {{"l1", miss_level(b.l1.misses - a.l1.misses, b.l1_misses_filled - a.l1_misses_filled,
                            b.l1_miss_service_cycles - a.l1_miss_service_cycles,
                            b.l1.mshr_stall_cycles - a.l1.mshr_stall_cycles)},
          {"l2", miss_level(b.l2.misses - a.l2.misses, b.l2_misses_filled - a.l2_misses_filled,
                            b.l2_miss_service_cycles - a.l2_miss_service_cycles,
                            b.l2.mshr_stall_cycles - a.l2.mshr_stall_cycles)}};
}

std::string run_statistics_lines(const StatsSample& end, const RunStatistics* statistics) {
  LatencyDistribution all;
  for (const LatencyDistribution& d : end.latency_by_kind) all.merge(d);
  std::string s = fmt::format("  ray latency percentiles (cycles)  p50 {}  p90 {}  p95 {}  p99 {}  max {}\n",
                              all.percentile(50), all.percentile(90), all.percentile(95), all.percentile(99), all.max());
  const nlohmann::json miss = RunStatistics::miss_latency_json(StatsSample{}, end);
  if (!miss.is_null())
    s += fmt::format("  mean miss latency (lookup to data, cycles)  L1 {:.1f}  L2 {:.1f}\n",
                     miss["l1"]["mean_cycles"].get<double>(), miss["l2"]["mean_cycles"].get<double>());
  if (statistics && statistics->options().warmup() && !statistics->measured_json().is_null()) {
    const nlohmann::json w = statistics->warmup_json(), m = statistics->measured_json();
    s += fmt::format("  after the warm-up (from cycle {}, {} rays excluded): {} rays in {} cycles, rays/cycle {:.4f}, "
                     "latency p50 {} p99 {}\n",
                     w["measured_from_cycle"].get<uint64_t>(), w["excluded_rays"].get<uint64_t>(),
                     m["rays"].get<uint64_t>(), m["cycles"].get<uint64_t>(), m["rays_per_cycle"].get<double>(),
                     m["latency_distribution"]["overall"]["p50"].get<uint64_t>(),
                     m["latency_distribution"]["overall"]["p99"].get<uint64_t>());
  }
  return s;
}

nlohmann::json latency_distribution_json(const std::array<LatencyDistribution, kRayKindCount>& by_kind) {
  LatencyDistribution all;
  nlohmann::json kinds = nlohmann::json::object();
  for (int k = 0; k < kRayKindCount; ++k) {
    all.merge(by_kind[k]);
    if (by_kind[k].rays()) kinds[ray_kind_name(static_cast<RayKind>(k))] = by_kind[k].summary_json();
  }
  return {{"percentile_rule", "nearest rank"},
          {"overall", all.summary_json()},
          {"by_kind", std::move(kinds)},
          {"log2_histogram", all.log2_histogram_json()}};
}

}  // namespace vbsim::hw
