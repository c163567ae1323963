#include "hw/sampling/sampled_feed.h"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>

#include "hw/accelerator.h"
#include "hw/sampling/sample_estimator.h"

namespace vbsim::hw {

SampledFeed::SampledFeed(const SamplingConfig& config, RayFeed inner, RayResultSink sink)
    : config_(config), plan_(config), inner_(std::move(inner)), sink_(std::move(sink)) {
  check_sampling_config(config_);
}

bool SampledFeed::peek() {
  if (stashed_) return true;
  if (ended_ || !inner_(stash_)) {
    ended_ = true;
    return false;
  }
  stash_pos_ = pos_++;
  stash_detailed_ = decide_detailed(stash_pos_);
  stashed_ = true;
  return true;
}

bool SampledFeed::decide_detailed(uint64_t pos) {
  if (plan_.in_head(pos) || plan_.in_tail(pos)) return true;
  if (!active_ || !plan_.detailed(pos)) return false;
  const uint64_t start = plan_.next_measured_start(pos);
  if (start != planned_start_) {  // the first ray of a new measured unit's warm-up (or of the unit)
    if (start < plan_.tail_start() && error_reached()) {
      active_ = false;
      stop_reason_ = fmt::format("error target reached at trace position {}", pos);
      return false;
    }
    planned_start_ = start;
  }
  return true;
}

bool SampledFeed::next_detailed(TraceRay& out) {
  for (;;) {
    if (!peek()) {
      // The trace ended: the last unit holds the rays it got.
      if (!units_.empty() && !units_.back().ended) {
        MeasuredUnit& u = units_.back();
        u.rays = detailed_ - u.detailed_start;
        for (Instant& i : pending_)
          if (i.unit == units_.size() - 1 && i.end) i.count = u.detailed_start + u.rays;
        cross(last_finish_cycle_);
      }
      if (!units_.empty()) {
        MeasuredUnit& u = units_.back();
        u.drained = u.stratum == MeasuredUnit::Stratum::Body && u.detailed_start + u.rays == detailed_ &&
                    u.trace_start + u.rays < pos_;
      }
      return false;
    }
    if (stash_detailed_) break;
    acc_->fast_forward(*this);  // the run of fast-forwarded rays up to the next detailed one
  }
  out = stash_;
  stashed_ = false;
  using Stratum = MeasuredUnit::Stratum;
  const uint64_t p = stash_pos_;
  if (p == 0 && plan_.head() > 0) begin_unit(p, Stratum::Head, plan_.head());
  else if (plan_.starts_measured_unit(p)) begin_unit(p, Stratum::Body, plan_.unit_rays(plan_.body_unit(p)));
  else if (p == plan_.tail_start()) begin_unit(p, Stratum::Tail, config_.total - p);
  if (stretches_.empty() || stretches_.back().second + (detailed_ - stretches_.back().first) != stash_pos_)
    stretches_.emplace_back(detailed_, stash_pos_);
  ++detailed_;
  return true;
}

bool SampledFeed::next_fast_forward(TraceRay& out) {
  if (!peek() || stash_detailed_) return false;
  out = stash_;
  taken_pos_ = stash_pos_;
  stashed_ = false;
  return true;
}

void SampledFeed::begin_unit(uint64_t pos, MeasuredUnit::Stratum stratum, uint64_t rays) {
  MeasuredUnit u;
  u.stratum = stratum;
  u.trace_start = pos;
  u.detailed_start = detailed_;
  u.rays = rays;
  units_.push_back(u);
  const size_t k = units_.size() - 1;
  pending_.push_back({u.detailed_start, k, false});
  pending_.push_back({u.detailed_start + u.rays, k, true});
  cross(last_finish_cycle_);  // every detailed ray before it may have finished already
}

void SampledFeed::detailed_done(const TraceRay& tr, const RayOutcome& out, uint64_t cycle, uint64_t index) {
  ++finished_;
  last_finish_cycle_ = cycle;
  cross(cycle);
  if (sink_) sink_(tr, out, cycle, trace_position(index));
}

uint64_t SampledFeed::trace_position(uint64_t index) const {
  // The last stretch starting at or before `index`.
  const auto after = std::upper_bound(stretches_.begin(), stretches_.end(), index,
                                      [](uint64_t i, const std::pair<uint64_t, uint64_t>& s) { return i < s.first; });
  const auto& s = *std::prev(after);
  return s.second + (index - s.first);
}

void SampledFeed::cross(uint64_t cycle) {
  while (!pending_.empty() && pending_.front().count <= finished_) {
    const Instant i = pending_.front();
    pending_.pop_front();
    MeasuredUnit& u = units_[i.unit];
    const uint64_t at = i.count == 0 ? 0 : cycle;
    if (i.end) {
      u.end_cycle = at;
      u.end = snapshot();
      u.ended = true;
    } else {
      u.start_cycle = at;
      u.start = snapshot();
      u.started = true;
    }
  }
}

CacheSnapshot SampledFeed::snapshot() const {
  CacheSnapshot s;
  if (!acc_) return s;
  for (size_t c = 0; c < acc_->cores(); ++c)
    if (const L1Cache* l1 = acc_->core(c).l1()) {
      const LevelCounters k = l1->counters();
      s.l1_hits += k.hits;
      s.l1_accesses += k.accesses;
    }
  if (const L2Cache* l2 = acc_->l2()) {
    const LevelCounters k = l2->counters();
    s.l2_hits = k.hits;
    s.l2_accesses = k.accesses;
  }
  return s;
}

std::vector<const MeasuredUnit*> SampledFeed::complete_units() const {
  std::vector<const MeasuredUnit*> out;
  for (const MeasuredUnit& u : units_)
    if (u.stratum == MeasuredUnit::Stratum::Body && u.started && u.ended && u.rays > 0 && !u.drained)
      out.push_back(&u);
  return out;
}

const MeasuredUnit* SampledFeed::stratum(MeasuredUnit::Stratum which) const {
  for (const MeasuredUnit& u : units_)
    if (u.stratum == which && u.started && u.ended) return &u;
  return nullptr;
}

bool SampledFeed::error_reached() const {
  if (config_.error <= 0) return false;
  std::vector<UnitMeasure> m;
  for (const MeasuredUnit* u : complete_units())
    m.push_back({static_cast<double>(u->end_cycle - u->start_cycle), static_cast<double>(u->rays)});
  if (m.size() < config_.min_units) return false;
  return ratio_estimate(m, config_.confidence, 0).relative() <= config_.error;
}

}  // namespace vbsim::hw
