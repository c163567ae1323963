// ReplayStats: what a replay counted, per ray kind, and its JSON form (the
// `--stats` file: config, rays, verdicts, by_kind, avoidance, traversal, sim).
#pragma once
#include <array>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "datapath/candidate_filter.h"
#include "datapath/closest_hit.h"
#include "datapath/ray.h"
#include "replay/replay_options.h"
#include "replay/verdict.h"

namespace vbsim {

/// Counters of one ray kind (or of all rays).
struct KindStats {
  uint64_t rays = 0;
  uint64_t hits = 0;                        ///< rays that returned a hit (shadow: occluded)
  uint64_t children = 0;                    ///< rays with a parent surface (parent_prim >= 0)
  std::array<uint64_t, kVerdictCount> verdicts{};
  uint64_t emission_fallbacks = 0;  ///< rays where an emission step lacked parent data
  uint64_t offset_fallbacks = 0;    ///< rays an offset placed off its reference (degenerate normal)
  uint64_t incomplete_excluded = 0;  ///< rays marked `incomplete`, left unscored
  uint64_t incomplete_scored = 0;    ///< rays marked `incomplete`, scored as asked (score_incomplete)
  CandidateCounters candidates;
  TraversalCounters traversal;

  void add(const KindStats& o);
};

struct ReplayStats {
  std::array<KindStats, kRayKindCount> by_kind;
  std::string mode = "functional";
  double wall_s = 0.0;
  bool partial = false;
  uint64_t rays_dropped = 0;  ///< a stopped cycle-level run: rays read but dropped in flight

  KindStats total() const;
  /// The stats JSON, with `config` the effective configuration.
  nlohmann::json to_json(const nlohmann::json& config) const;
  /// A short human summary (rays, verdicts, rejection rate, speed).
  std::string summary() const;
};

/// The four kinds of ray an emission-time method treats apart: with or without
/// a parent surface (`child`), shadow or not; and how many of each a replay had.
struct RayCategory {
  bool child = false, shadow = false;
  uint64_t rays = 0;
};
std::array<RayCategory, 4> ray_categories(const ReplayStats& stats);

/// The method's operations over a replay, from its config's `cost_ops`: each
/// ray's emission and result operations (`by_ray`, by ray category), plus the
/// per-candidate and per-suspect costs times the counts measured.
uint64_t method_ops_total(const nlohmann::json& cost_ops, const ReplayStats& stats);

/// The effective configuration of a replay as JSON (method, tester, parameters).
nlohmann::json replay_config_json(const ReplayOptions& opt);

}  // namespace vbsim
