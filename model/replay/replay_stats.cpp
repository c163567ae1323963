#include "replay/replay_stats.h"

#include "datapath/method_costs.h"

#include <fmt/format.h>

namespace vbsim {

namespace {

nlohmann::json verdicts_json(const KindStats& k) {
  nlohmann::json j;
  for (int v = 0; v < kVerdictCount; ++v) j[verdict_name(static_cast<Verdict>(v))] = k.verdicts[v];
  return j;
}

double ratio(uint64_t num, uint64_t den) { return den ? static_cast<double>(num) / den : 0.0; }

nlohmann::json avoidance_json(const CandidateCounters& c) {
  nlohmann::json j = {{"candidates", c.candidates},
                      {"suspects", c.suspects},
                      {"rejected", c.rejected},
                      {"suspect_rate", ratio(c.suspects, c.candidates)},
                      {"rejection_rate", ratio(c.rejected, c.candidates)},
                      {"rejected_by",
                       {{"primid", c.rejected_primid},
                        {"sign_only", c.rejected_sign_only},
                        {"normal", c.invalid_normal},
                        {"ray", c.invalid_ray},
                        {"component", c.invalid_component}}}};
  // Ray masks (only traces that declare them have candidates they hide).
  if (c.rejected_mask > 0) j["rejected_by"]["mask"] = c.rejected_mask;
  return j;
}

nlohmann::json traversal_json(const TraversalCounters& t, uint64_t rays) {
  return {{"node_visits", t.node_visits},
          {"box_tests", t.box_tests},
          {"triangle_tests", t.triangle_tests},
          {"stack_pushes", t.stack_pushes},
          {"stack_pops", t.stack_pops},
          {"node_visits_per_ray", ratio(t.node_visits, rays)},
          {"triangle_tests_per_ray", ratio(t.triangle_tests, rays)}};
}

}  // namespace

void KindStats::add(const KindStats& o) {
  rays += o.rays;
  hits += o.hits;
  children += o.children;
  for (int v = 0; v < kVerdictCount; ++v) verdicts[v] += o.verdicts[v];
  emission_fallbacks += o.emission_fallbacks;
  offset_fallbacks += o.offset_fallbacks;
  incomplete_excluded += o.incomplete_excluded;
  incomplete_scored += o.incomplete_scored;
  candidates.add(o.candidates);
  traversal.add(o.traversal);
}

KindStats ReplayStats::total() const {
  KindStats t;
  for (const KindStats& k : by_kind) t.add(k);
  return t;
}

std::array<RayCategory, 4> ray_categories(const ReplayStats& s) {
  std::array<RayCategory, 4> c;
  for (int i = 0; i < 4; ++i) c[i].child = i & 1, c[i].shadow = i & 2;
  for (int k = 0; k < kRayKindCount; ++k) {
    const KindStats& ks = s.by_kind[k];
    const int shadow = static_cast<RayKind>(k) == RayKind::Shadow ? 2 : 0;
    c[1 | shadow].rays += ks.children;
    c[shadow].rays += ks.rays - ks.children;
  }
  return c;
}

/// The method's operation counts: the totals of method_costs.h, and the
/// emission and result operations of each kind of ray (`by_ray`: the parts of
/// an emission-time method act on some rays only), which method_ops_json uses.
static nlohmann::json method_cost_json(const SelfIntersectionMethod& m) {
  const MethodCost c = method_cost(m);
  nlohmann::json by_ray;
  for (const bool child : {false, true})
    for (const bool shadow : {false, true})
      by_ray[std::string(child ? "child" : "lone") + (shadow ? "_shadow" : "")] =
          emission_ops_for(m, child, shadow).total() + result_ops_for(m, shadow).total();
  return {{"emission", c.emission}, {"result", c.result}, {"candidate", c.candidate}, {"suspect", c.suspect},
          {"by_ray", by_ray}};
}

/// The method's operations over the replay: each ray's emission and result
/// operations (by_ray: those of its kind), candidate and suspect costs times
/// the counts measured (method_costs.h).
uint64_t method_ops_total(const nlohmann::json& cost, const ReplayStats& s) {
  const KindStats t = s.total();
  uint64_t total = cost.value("candidate", 0) * t.candidates.candidates + cost.value("suspect", 0) * t.candidates.suspects;
  for (const RayCategory& c : ray_categories(s)) {
    const std::string key = std::string(c.child ? "child" : "lone") + (c.shadow ? "_shadow" : "");
    total += c.rays * (cost.contains("by_ray") ? cost["by_ray"].value(key, 0)
                                               : cost.value("emission", 0) + cost.value("result", 0));
  }
  return total;
}

static nlohmann::json method_ops_json(const nlohmann::json& cost, const ReplayStats& s) {
  const uint64_t total = method_ops_total(cost, s);
  return {{"total", total}, {"per_ray", ratio(total, s.total().rays)}};
}

nlohmann::json ReplayStats::to_json(const nlohmann::json& config) const {
  const KindStats t = total();
  nlohmann::json j;
  j["config"] = config;
  j["rays"] = t.rays;
  j["hits"] = t.hits;
  j["verdicts"] = verdicts_json(t);
  j["emission_fallbacks"] = t.emission_fallbacks;
  j["offset_fallbacks"] = t.offset_fallbacks;
  if (t.incomplete_excluded + t.incomplete_scored > 0)  // only traces that mark rays (captures) carry it
    j["incomplete"] = {{"excluded", t.incomplete_excluded}, {"scored", t.incomplete_scored}};
  nlohmann::json kinds = nlohmann::json::object();
  for (int k = 0; k < kRayKindCount; ++k) {
    const KindStats& s = by_kind[k];
    if (s.rays == 0) continue;
    kinds[ray_kind_name(static_cast<RayKind>(k))] = {{"rays", s.rays},
                                                     {"hits", s.hits},
                                                     {"verdicts", verdicts_json(s)},
                                                     {"avoidance", avoidance_json(s.candidates)},
                                                     {"traversal", traversal_json(s.traversal, s.rays)}};
  }
  j["by_kind"] = kinds;
  j["avoidance"] = avoidance_json(t.candidates);
  j["traversal"] = traversal_json(t.traversal, t.rays);
  if (config.contains("cost_ops")) j["method_ops"] = method_ops_json(config["cost_ops"], *this);
  j["sim"] = {{"mode", mode},
              {"wall_s", wall_s},
              {"rays_per_s", wall_s > 0 ? t.rays / wall_s : 0.0},
              {"partial", partial}};
  if (partial && mode == "cycle") j["sim"]["rays_dropped"] = rays_dropped;
  return j;
}

std::string ReplayStats::summary() const {
  const KindStats t = total();
  std::string s = fmt::format("rays {:>10}   hits {:>10}\n", t.rays, t.hits);
  s += "verdicts ";
  for (int v = 0; v < kVerdictCount; ++v)
    s += fmt::format(" {} {}", verdict_name(static_cast<Verdict>(v)), t.verdicts[v]);
  s += "\n";
  for (int k = 0; k < kRayKindCount; ++k) {
    const KindStats& ks = by_kind[k];
    if (ks.rays == 0) continue;
    s += fmt::format("  {:<8} {:>8} rays  correct {:>8}  self_hit {:>6}  false_hit {:>6}  missed {:>6}  unscored {:>6}\n",
                     ray_kind_name(static_cast<RayKind>(k)), ks.rays, ks.verdicts[0], ks.verdicts[1],
                     ks.verdicts[2], ks.verdicts[3], ks.verdicts[4]);
  }
  if (t.incomplete_excluded > 0)
    s += fmt::format("incomplete: {} rays marked incomplete left unscored (their renderer's answer involved what the "
                     "trace does not hold; --score-incomplete scores them)\n", t.incomplete_excluded);
  if (t.incomplete_scored > 0) s += fmt::format("incomplete: {} rays marked incomplete scored as asked\n", t.incomplete_scored);
  const CandidateCounters& c = t.candidates;
  s += fmt::format("avoidance: {} candidates, {} suspects ({:.3f}%), {} rejected ({:.3f}% of candidates)\n",
                   c.candidates, c.suspects, 100.0 * ratio(c.suspects, c.candidates), c.rejected,
                   100.0 * ratio(c.rejected, c.candidates));
  s += fmt::format("speed: {:.3f} s wall, {:.0f} rays/s ({}{})\n", wall_s,
                   wall_s > 0 ? t.rays / wall_s : 0.0, mode, partial ? ", partial" : "");
  return s;
}

namespace {

/// The BVH build options as a config's `bvh` object (read back by replay_config.cpp).
nlohmann::json bvh_options_json(const BvhBuildOptions& b) {
  nlohmann::json j = {{"builder", bvh_builder_name(b.builder)},
                      {"quality", bvh_quality_name(b.quality)},
                      {"max_leaf_size", b.max_leaf_size},
                      {"traversal_cost", b.traversal_cost},
                      {"sah_block_size", b.sah_block_size},
                      {"width", b.width}};
  if (b.low_precision.enabled)
    j["low_precision"] = {{"mantissa_bits", b.low_precision.mantissa_bits},
                          {"t_trav_high", b.low_precision.t_trav_high},
                          {"t_trav_low", b.low_precision.t_trav_low},
                          {"narrow_arithmetic", b.low_precision.narrow_arithmetic}};
  return j;
}

}  // namespace

nlohmann::json replay_config_json(const ReplayOptions& opt) {
  const SelfIntersectionMethod& m = opt.method;
  const AvoidanceConfig& a = m.avoidance;
  nlohmann::json j = {{"method", m.name()},
          {"tester", tester_name(opt.tester)},
          {"hitpoint", hit_point_mode_name(opt.hit_point)},
          {"bits_per_ray", m.bits_per_ray()},
          {"cost_ops", method_cost_json(m)},
          {"shadow_any_hit", opt.any_hit_for_shadow},
          {"bvh", bvh_options_json(opt.bvh)},
          {"tmin_eps", m.tmin_eps},
          {"offset_normal_eps", m.offset_normal_eps},
          {"offset_direction_eps", m.offset_direction_eps},
          {"adaptive", {{"origin", m.adaptive.origin},
                        {"float_scale", m.adaptive.float_scale},
                        {"int_scale", m.adaptive.int_scale}}},
          {"validity_bit",
           {{"policy", avoidance_policy_name(a.policy)},
            {"eps_mode", epsilon_mode_name(a.eps_mode)},
            {"eps", a.eps},
            {"guard_bits", a.guard_bits},
            {"min_exponent", a.min_exponent},
            {"tests", {{"normal", a.test_normal}, {"ray", a.test_ray}, {"component", a.test_component}}},
            {"component_scale", a.component_scale},
            {"weights", {{"normal", a.weight_normal}, {"ray", a.weight_ray}, {"component", a.weight_component}}}}}};
  if (opt.reference_answers) j["answers"] = "reference";  // the renderer's own, judged; no search
  return j;
}

}  // namespace vbsim
