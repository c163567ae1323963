#include "fit/fit_search.h"

#include <algorithm>
#include <mutex>

#include "replay/functional_replayer.h"
#include "parallel/parallel_for.h"
#include "trace/checked_trace_source.h"
#include "trace/trace_file.h"

namespace vbsim {

namespace {

/// One ray's verdict under the parameter at grid index i.
struct RayJudge {
  const FitParameter& param;
  const FitTrace& trace;
  size_t ray;
  Verdict at(int i) const {
    const ReplayOptions opt = param.options_at(i);
    const CandidateFilter filter(opt.method, trace.scene.scene.mask_table());
    KindStats scratch;
    return replay_one_ray(trace.rays()[ray], trace.scene.scene, trace.scene.bvh, opt, filter,
                          trace.blocks->parents_for(ray), scratch)
        .verdict;
  }
};

/// Lowest index from which the ray has no self_hit (top + 1: not within the grid).
int lowest_acceptable(const RayJudge& j, int top) {
  if (j.at(0) != Verdict::SelfHit) return 0;
  if (j.at(top) == Verdict::SelfHit) return top + 1;
  int bad = 0, good = top;
  while (good - bad > 1) {
    const int mid = bad + (good - bad) / 2;
    (j.at(mid) == Verdict::SelfHit ? bad : good) = mid;
  }
  return good;
}

/// Highest index up to which the ray is not missed (-1: missed even at 0).
int highest_acceptable(const RayJudge& j, int top) {
  if (j.at(top) != Verdict::Missed) return top;
  if (j.at(0) == Verdict::Missed) return -1;
  int good = 0, bad = top;
  while (bad - good > 1) {
    const int mid = good + (bad - good) / 2;
    (j.at(mid) == Verdict::Missed ? bad : good) = mid;
  }
  return good;
}

FitRay name_ray(const FitTrace& t, size_t i) {
  return {t.path, t.rays()[i].id, ray_kind_name(t.rays()[i].kind)};
}

bool acceptable(Verdict v) { return v != Verdict::SelfHit && v != Verdict::Missed; }

/// Positions (into `rays`) of the rays with self_hit or missed at grid index i, ascending.
std::vector<size_t> failing_rays(const FitParameter& param, const std::vector<FitTrace>& traces,
                                 const std::vector<std::pair<size_t, size_t>>& rays, int i, int threads) {
  std::vector<uint8_t> bad(rays.size());
  parallel_for(rays.size(), threads, [&](size_t k) {
    bad[k] = !acceptable(RayJudge{param, traces[rays[k].first], rays[k].second}.at(i));
  });
  std::vector<size_t> out;
  for (size_t k = 0; k < rays.size(); ++k)
    if (bad[k]) out.push_back(k);
  return out;
}

/// The first 10 of `which` as named rays.
std::vector<FitRay> name_rays(const std::vector<FitTrace>& traces, const std::vector<std::pair<size_t, size_t>>& rays,
                              const std::vector<size_t>& which) {
  std::vector<FitRay> out;
  for (size_t k = 0; k < which.size() && out.size() < 10; ++k)
    out.push_back(name_ray(traces[rays[which[k]].first], rays[which[k]].second));
  return out;
}

/// Every scored ray as (trace, ray) pairs, in trace order.
std::vector<std::pair<size_t, size_t>> scored_rays(const std::vector<FitTrace>& traces) {
  std::vector<std::pair<size_t, size_t>> out;
  for (size_t t = 0; t < traces.size(); ++t)
    for (size_t i = 0; i < traces[t].rays().size(); ++i)
      if (traces[t].rays()[i].has_expect) out.emplace_back(t, i);
  return out;
}

}  // namespace

FitTrace load_fit_trace(const std::string& path) {
  FitTrace t;
  t.path = path;
  t.file = open_trace(path);
  t.source = std::make_unique<CheckedTraceSource>(*t.file, TraceConsistencyChecker::Options{});
  t.scene = load_trace_scene(t.source->header());
  check_traversal_depth(t.scene.bvh);
  t.source->set_triangle_count(t.scene.scene.size());
  t.blocks = std::make_unique<TraceBlocks>(*t.source);
  t.blocks->next_block(0);
  return t;
}

FitResult fit_parameter(const FitParameter& param, const std::vector<FitTrace>& traces, int threads) {
  const auto rays = scored_rays(traces);
  const int top = param.top_index;
  std::vector<int> lo(rays.size()), hi(rays.size());
  parallel_for(rays.size(), threads, [&](size_t k) {
    const RayJudge j{param, traces[rays[k].first], rays[k].second};
    lo[k] = lowest_acceptable(j, top);
    hi[k] = highest_acceptable(j, top);
  });

  FitResult r;
  r.key = param.key;
  r.description = param.description;
  r.rays = rays.size();
  r.searched_low = param.value(1);
  r.searched_high = param.value(top);
  r.resolution = param.integer ? 0.0 : param.value(2) / param.value(1) - 1;
  r.lowest_index = 0;
  r.highest_index = top;
  // The first ray with the largest lower end and the first with the smallest upper end.
  for (size_t k = 0; k < rays.size(); ++k) {
    if (lo[k] > r.lowest_index) {
      r.lowest_index = lo[k];
      r.needs_at_least = name_ray(traces[rays[k].first], rays[k].second);
    }
    if (hi[k] < r.highest_index) {
      r.highest_index = hi[k];
      r.needs_at_most = name_ray(traces[rays[k].first], rays[k].second);
    }
  }
  r.lowest = param.value(std::min(r.lowest_index, top));
  r.below = param.value(std::max(r.lowest_index - 1, 0));
  r.highest = param.value(std::max(r.highest_index, 0));
  r.above = param.value(std::min(r.highest_index + 1, top));
  r.self_hit_at_top = r.lowest_index > top;
  r.missed_at_zero = r.highest_index < 0;
  r.feasible = !r.self_hit_at_top && !r.missed_at_zero && r.lowest_index <= r.highest_index;
  if (!r.feasible) return r;

  // The check: every ray at the answer, and one grid step below it. When a ray
  // fails it (verdicts not monotone), the answer moves up the grid until the
  // failing rays pass and the whole check passes, or the upper end is reached.
  std::vector<size_t> failing = failing_rays(param, traces, rays, r.lowest_index, threads);
  r.check_failures = name_rays(traces, rays, failing);
  for (int i = r.lowest_index + 1; !failing.empty() && i <= r.highest_index; ++i) {
    bool pass = true;
    for (size_t k : failing) pass = pass && acceptable(RayJudge{param, traces[rays[k].first], rays[k].second}.at(i));
    if (!pass) continue;
    failing = failing_rays(param, traces, rays, i, threads);
    if (failing.empty()) {
      r.repaired_index = i;
      r.repaired = param.value(i);
    }
  }
  if (!r.check_failures.empty() && r.repaired_index < 0) r.feasible = false;
  const int answer = r.repaired_index >= 0 ? r.repaired_index : r.lowest_index;
  std::mutex m;
  parallel_for(rays.size(), threads, [&](size_t k) {
    const RayJudge j{param, traces[rays[k].first], rays[k].second};
    const Verdict v = j.at(answer);
    const bool below_self = r.lowest_index > 0 && j.at(r.lowest_index - 1) == Verdict::SelfHit;
    std::lock_guard<std::mutex> lock(m);
    r.check_self_hit += v == Verdict::SelfHit;
    r.check_missed += v == Verdict::Missed;
    r.check_false_hit += v == Verdict::FalseHit;
    r.below_self_hit += below_self;
  });
  r.checked = true;
  return r;
}

}  // namespace vbsim
