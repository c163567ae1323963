#include "score/score_table.h"

#include <fmt/format.h>

#include "energy/operation_energy.h"
#include "score/wilson_interval.h"

namespace vbsim {

namespace {

constexpr double kPerMillion = 1e6;
/// The verdicts a table reports (unscored rays are counted but not rated).
constexpr Verdict kRated[] = {Verdict::Correct, Verdict::SelfHit, Verdict::FalseHit, Verdict::Missed};

double ratio(uint64_t num, uint64_t den) { return den ? static_cast<double>(num) / den : 0.0; }


nlohmann::json rate_json(uint64_t count, uint64_t of) {
  const Proportion p = wilson_interval(count, of);
  return {{"rate", kPerMillion * p.estimate}, {"lower", kPerMillion * p.lower}, {"upper", kPerMillion * p.upper}};
}

nlohmann::json row_json(const ScoreCell& cell, const char* kind, const KindStats& k) {
  const uint64_t scored = k.rays - k.verdicts[static_cast<int>(Verdict::Unscored)];
  const uint64_t errors = k.verdicts[static_cast<int>(Verdict::SelfHit)] +
                          k.verdicts[static_cast<int>(Verdict::FalseHit)] + k.verdicts[static_cast<int>(Verdict::Missed)];
  nlohmann::json counts, rates;
  for (int v = 0; v < kVerdictCount; ++v) counts[verdict_name(static_cast<Verdict>(v))] = k.verdicts[v];
  for (Verdict v : kRated) rates[verdict_name(v)] = rate_json(k.verdicts[static_cast<int>(v)], scored);
  const CandidateCounters& c = k.candidates;
  return {{"family", cell.family},
          {"method", cell.method},
          {"tester", tester_name(cell.tester)},
          {"kind", kind},
          {"rays", k.rays},
          {"scored", scored},
          {"counts", counts},
          {"per_million", rates},
          {"errors", {{"count", errors}, {"per_million", rate_json(errors, scored)}}},
          {"emission_fallbacks", k.emission_fallbacks},
          {"offset_fallbacks", k.offset_fallbacks},
          {"avoidance",
           {{"candidates", c.candidates},
            {"suspects", c.suspects},
            {"rejected", c.rejected},
            {"suspect_rate", ratio(c.suspects, c.candidates)},
            {"rejection_rate", ratio(c.rejected, c.candidates)}}}};
}

}  // namespace

std::string format_per_million(double x) {
  if (x == 0) return "0";
  if (x >= 99.5) return fmt::format("{:.0f}", x);
  if (x >= 0.995) return fmt::format("{:.1f}", x);
  return fmt::format("{:.2g}", x);
}

nlohmann::json score_json(const std::vector<ScoreFamily>& families, const std::vector<ScoreCell>& cells,
                          const std::string& command, const TechFile* tech) {
  const TechFile shipped = tech ? TechFile{} : load_tech_file(default_tech_path());
  const TechFile& t = tech ? *tech : shipped;
  nlohmann::json j;
  j["command"] = command;
  j["confidence"] = {{"level", 0.95}, {"z", kZ95}, {"interval", "wilson"}, {"per", kPerMillion}};
  j["families"] = nlohmann::json::array();
  for (const ScoreFamily& f : families)
    j["families"].push_back({{"name", f.name}, {"traces", f.traces.size()}, {"generator", f.generator}});
  j["rows"] = nlohmann::json::array();
  for (const ScoreCell& cell : cells) {
    const KindStats total = cell.stats.total();
    nlohmann::json all = row_json(cell, "all", total);
    all["rays_per_s"] = cell.stats.wall_s > 0 ? total.rays / cell.stats.wall_s : 0.0;
    all["config"] = cell.config;
    all["ops_per_ray"] = ratio(method_ops_total(cell.config["cost_ops"], cell.stats), total.rays);
    const OperationEnergy e = operation_energy(t, cell.options.method, cell.tester, cell.stats);
    all["energy"] = {{"tech", t.path},
                     {"per_ray_pj", per_ray(e.total(), total.rays)},
                     {"method_per_ray_pj", per_ray(e.method, total.rays)}};
    if (cell.has_cycles)
      all["cycle"] = {{"preset", cell.cycle_preset},
                      {"rays", cell.cycle_rays},
                      {"cycles", cell.cycles},
                      {"cycles_per_ray", ratio(cell.cycles, cell.cycle_rays)},
                      {"rays_per_cycle", ratio(cell.cycle_rays, cell.cycles)},
                      // Every cost of the same runs: energy (operations, memory, leakage; the
                      // replay's hw.energy.per_ray_pj) and the chip's area (hw.area.chip_mm2).
                      {"tech", t.path},
                      {"total_pj", cell.cycle_total_pj},
                      {"energy_per_ray_pj", per_ray(cell.cycle_total_pj, cell.cycle_rays)},
                      {"chip_mm2", cell.chip_mm2}};
    j["rows"].push_back(std::move(all));
    KindStats secondary;  // every ray with a parent surface: the self-intersection problem
    for (int k = 0; k < kRayKindCount; ++k)
      if (static_cast<RayKind>(k) != RayKind::Primary) secondary.add(cell.stats.by_kind[k]);
    j["rows"].push_back(row_json(cell, kSecondaryKind, secondary));
    for (int k = 0; k < kRayKindCount; ++k)
      if (cell.stats.by_kind[k].rays)
        j["rows"].push_back(row_json(cell, ray_kind_name(static_cast<RayKind>(k)), cell.stats.by_kind[k]));
  }
  return j;
}

}  // namespace vbsim
