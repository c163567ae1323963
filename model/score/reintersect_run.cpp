#include "score/reintersect_run.h"

#include <fmt/format.h>

#include <chrono>
#include <mutex>

#include "gen/pbrt_reintersect.h"
#include "replay/functional_replayer.h"
#include "parallel/parallel_for.h"
#include "score/score_table.h"
#include "score/wilson_interval.h"

namespace vbsim {

namespace {

/// Triangles per job handed to a worker.
constexpr int64_t kTrialsPerJob = 64;

/// Replays one trial with every configuration, adding into `counts`.
void replay_trial(const PbrtReintersectTrial& trial, const std::vector<ScoreConfig>& configs,
                  const std::vector<CandidateFilter>& filters, std::vector<ReintersectCounts>& counts) {
  const Scene scene = make_scene({trial.tri});
  const Bvh bvh = build_bvh(scene);
  ParentRays parents;
  for (const TraceRay& tr : trial.rays) parents[tr.id] = {tr.o, tr.d};
  for (size_t c = 0; c < configs.size(); ++c) {
    ReintersectCounts& n = counts[c];
    for (const TraceRay& tr : trial.rays) {
      KindStats ks;
      // Parents precede their children in a trial, so the full map is what a stream would have seen.
      const RayOutcome out = replay_one_ray(tr, scene, bvh, configs[c].options, filters[c], find_parent(parents, tr.parent), ks);
      n.offset_fallbacks += ks.offset_fallbacks;
      if (tr.kind == RayKind::Primary) {
        ++n.camera_rays;
        n.camera_misses += out.answer < 0;
      } else if (tr.kind == RayKind::Diffuse) {
        ++n.spawn_rays;
        n.spawn_rehits += out.answer >= 0;
      } else {
        ++n.spawn_to_rays;
        n.spawn_to_rehits += out.answer >= 0;
      }
    }
  }
}

nlohmann::json rate_json(uint64_t k, uint64_t n) {
  const Proportion p = wilson_interval(k, n);
  return {{"count", k}, {"of", n}, {"rate", 1e6 * p.estimate}, {"lower", 1e6 * p.lower}, {"upper", 1e6 * p.upper}};
}

std::string rate_text(const nlohmann::json& r) {
  return fmt::format("{} of {}: {} [{}, {}]", r["count"].get<uint64_t>(), r["of"].get<uint64_t>(),
                     format_per_million(r["rate"].get<double>()), format_per_million(r["lower"].get<double>()),
                     format_per_million(r["upper"].get<double>()));
}

}  // namespace

void ReintersectCounts::add(const ReintersectCounts& o) {
  camera_rays += o.camera_rays;
  camera_misses += o.camera_misses;
  spawn_rays += o.spawn_rays;
  spawn_rehits += o.spawn_rehits;
  spawn_to_rays += o.spawn_to_rays;
  spawn_to_rehits += o.spawn_to_rehits;
  offset_fallbacks += o.offset_fallbacks;
}

ReintersectResult run_reintersect(const ReintersectParams& params, const std::vector<ScoreConfig>& configs) {
  ReintersectResult r;
  r.params = params;
  r.configs = configs;
  r.counts.assign(configs.size(), {});
  std::vector<CandidateFilter> filters;
  for (const ScoreConfig& c : configs) filters.emplace_back(c.options.method);
  const auto start = std::chrono::steady_clock::now();
  const int64_t jobs = (params.triangles + kTrialsPerJob - 1) / kTrialsPerJob;
  std::mutex merge;
  parallel_for(static_cast<size_t>(jobs), params.threads, [&](size_t job) {
    std::vector<ReintersectCounts> local(configs.size());
    uint64_t degenerate = 0, skipped = 0;
    const int64_t lo = static_cast<int64_t>(job) * kTrialsPerJob;
    const int64_t hi = std::min(params.triangles, lo + kTrialsPerJob);
    for (int64_t k = lo; k < hi; ++k) {
      const PbrtReintersectTrial trial =
          pbrt_reintersect_trial(params.first + static_cast<uint64_t>(k), params.children, params.exp);
      degenerate += trial.degenerate;
      skipped += !trial.degenerate && !trial.camera_hit;
      if (!trial.degenerate) replay_trial(trial, configs, filters, local);
    }
    const std::lock_guard<std::mutex> lock(merge);
    r.degenerate += degenerate;
    r.skipped += skipped;
    for (size_t c = 0; c < configs.size(); ++c) r.counts[c].add(local[c]);
  });
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

nlohmann::json reintersect_json(const ReintersectResult& r, const std::string& command) {
  nlohmann::json j;
  j["command"] = command;
  j["protocol"] = "pbrt-v4 Triangle Reintersect";
  j["params"] = {{"first", r.params.first},
                 {"triangles", r.params.triangles},
                 {"children", r.params.children},
                 {"exp", r.params.exp}};
  j["degenerate"] = r.degenerate;
  j["skipped"] = r.skipped;
  j["confidence"] = {{"level", 0.95}, {"interval", "wilson"}, {"per", 1e6}};
  j["wall_s"] = r.wall_s;
  j["rows"] = nlohmann::json::array();
  for (size_t c = 0; c < r.configs.size(); ++c) {
    const ReintersectCounts& n = r.counts[c];
    j["rows"].push_back({{"method", r.configs[c].method},
                         {"tester", tester_name(r.configs[c].options.tester)},
                         {"camera_misses", rate_json(n.camera_misses, n.camera_rays)},
                         {"spawn_ray", rate_json(n.spawn_rehits, n.spawn_rays)},
                         {"spawn_ray_to", rate_json(n.spawn_to_rehits, n.spawn_to_rays)},
                         {"children", rate_json(n.spawn_rehits + n.spawn_to_rehits, n.spawn_rays + n.spawn_to_rays)},
                         {"offset_fallbacks", n.offset_fallbacks}});
  }
  return j;
}

std::string reintersect_markdown(const nlohmann::json& j) {
  const auto& p = j["params"];
  std::string md = fmt::format(
      "{} triangles RNG({}) .. RNG({}), {} SpawnRay and {} SpawnRayTo children each; {} dropped as degenerate, "
      "{} skipped (pbrt's test missed the camera ray). Re-hits per million child rays, 95% Wilson interval.\n\n",
      p["triangles"].get<int64_t>(), p["first"].get<uint64_t>(),
      p["first"].get<uint64_t>() + p["triangles"].get<uint64_t>() - 1, p["children"].get<int64_t>(),
      p["children"].get<int64_t>(), j["degenerate"].get<uint64_t>(), j["skipped"].get<uint64_t>());
  md += "| method | tester | child re-hits /M | SpawnRay re-hits | SpawnRayTo re-hits | camera misses | offset fallbacks |\n"
        "|---|---|---|---|---|---|---:|\n";
  for (const auto& r : j["rows"])
    md += fmt::format("| `{}` | {} | {} | {} | {} | {} of {} | {} |\n", r["method"].get<std::string>(),
                      r["tester"].get<std::string>(), rate_text(r["children"]), rate_text(r["spawn_ray"]),
                      rate_text(r["spawn_ray_to"]), r["camera_misses"]["count"].get<uint64_t>(),
                      r["camera_misses"]["of"].get<uint64_t>(), r["offset_fallbacks"].get<uint64_t>());
  return md;
}

}  // namespace vbsim
