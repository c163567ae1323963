#include "score/score_table.h"

#include <fmt/format.h>

#include <algorithm>

#include "score/wilson_interval.h"

namespace vbsim {

namespace {

constexpr double kPerMillion = 1e6;
/// The verdicts a table reports (unscored rays are counted but not rated).
constexpr Verdict kRated[] = {Verdict::Correct, Verdict::SelfHit, Verdict::FalseHit, Verdict::Missed};

double ratio(uint64_t num, uint64_t den) { return den ? static_cast<double>(num) / den : 0.0; }

nlohmann::json row_json(const ScoreCell& cell, const char* kind, const KindStats& k) {
  const uint64_t scored = k.rays - k.verdicts[static_cast<int>(Verdict::Unscored)];
  nlohmann::json counts, rates;
  for (int v = 0; v < kVerdictCount; ++v) counts[verdict_name(static_cast<Verdict>(v))] = k.verdicts[v];
  for (Verdict v : kRated) {
    const Proportion p = wilson_interval(k.verdicts[static_cast<int>(v)], scored);
    rates[verdict_name(v)] = {{"rate", kPerMillion * p.estimate},
                              {"lower", kPerMillion * p.lower},
                              {"upper", kPerMillion * p.upper}};
  }
  const CandidateCounters& c = k.candidates;
  return {{"family", cell.family},
          {"method", cell.method},
          {"tester", tester_name(cell.tester)},
          {"kind", kind},
          {"rays", k.rays},
          {"scored", scored},
          {"counts", counts},
          {"per_million", rates},
          {"emission_fallbacks", k.emission_fallbacks},
          {"offset_fallbacks", k.offset_fallbacks},
          {"avoidance",
           {{"candidates", c.candidates},
            {"suspects", c.suspects},
            {"rejected", c.rejected},
            {"suspect_rate", ratio(c.suspects, c.candidates)},
            {"rejection_rate", ratio(c.rejected, c.candidates)}}}};
}

std::string rate_cell(const nlohmann::json& r) {
  return fmt::format("{} [{}, {}]", format_per_million(r["rate"].get<double>()),
                     format_per_million(r["lower"].get<double>()),
                     format_per_million(r["upper"].get<double>()));
}

std::string percent(double x) { return x == 0 ? "0" : fmt::format("{:.3f}", 100 * x); }

/// Errors (self_hit + false_hit + missed) per million scored rays of an `all` row.
std::string errors_per_million(const nlohmann::json& r) {
  const auto& c = r["counts"];
  const uint64_t errors = c["self_hit"].get<uint64_t>() + c["false_hit"].get<uint64_t>() +
                          c["missed"].get<uint64_t>();
  return format_per_million(kPerMillion * ratio(errors, r["scored"].get<uint64_t>()));
}

/// One table per tester: methods down, families across, errors per million.
std::string summary_markdown(const nlohmann::json& score) {
  std::vector<std::string> families, methods, testers;
  const auto add = [](std::vector<std::string>& v, const std::string& x) {
    if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
  };
  for (const auto& f : score["families"]) add(families, f["name"].get<std::string>());
  for (const auto& r : score["rows"]) {
    add(methods, r["method"].get<std::string>());
    add(testers, r["tester"].get<std::string>());
  }
  std::string md;
  for (const std::string& tester : testers) {
    md += fmt::format("\n## Summary, {} tester: errors per million rays\n\n", tester);
    md += "self_hit + false_hit + missed per million scored rays, all ray kinds.\n\n| method |";
    for (const std::string& f : families) md += fmt::format(" {} |", f);
    md += "\n|---|";
    for (size_t i = 0; i < families.size(); ++i) md += "---:|";
    md += "\n";
    for (const std::string& m : methods) {
      md += fmt::format("| `{}` |", m);
      for (const std::string& f : families) {
        std::string cell = " ";
        for (const auto& r : score["rows"])
          if (r["kind"] == "all" && r["tester"] == tester && r["method"] == m && r["family"] == f)
            cell = errors_per_million(r);
        md += fmt::format(" {} |", cell);
      }
      md += "\n";
    }
  }
  return md;
}

}  // namespace

std::string format_per_million(double x) {
  if (x == 0) return "0";
  if (x >= 99.5) return fmt::format("{:.0f}", x);
  if (x >= 0.995) return fmt::format("{:.1f}", x);
  return fmt::format("{:.2g}", x);
}

nlohmann::json score_json(const std::vector<ScoreFamily>& families, const std::vector<ScoreCell>& cells,
                          const std::string& command) {
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
    j["rows"].push_back(std::move(all));
    for (int k = 0; k < kRayKindCount; ++k)
      if (cell.stats.by_kind[k].rays)
        j["rows"].push_back(row_json(cell, ray_kind_name(static_cast<RayKind>(k)), cell.stats.by_kind[k]));
  }
  return j;
}

std::string score_markdown(const nlohmann::json& score, const std::string& regenerate) {
  std::string md = "# Accuracy of every method\n\n";
  md += "Generated by `vbsim score`; do not edit by hand. Regenerate with:\n\n";
  md += fmt::format("    {}\n\n", regenerate);
  md += fmt::format("The command that scored the traces:\n\n    {}\n\n", score["command"].get<std::string>());
  md += "Each row: one method (with its parameters after `:`, see `vbsim score --help`) and tester "
        "on the rays of one kind (`all`: every kind). Verdicts are per million scored rays "
        "(rays with `expect`) with the 95% Wilson score interval in brackets; a zero count "
        "still has a non-zero upper bound. `suspect %` and `rejected %` are the avoidance "
        "unit's suspects and the filters' rejections per candidate hit. `rays/s`: functional "
        "replay speed of the configuration, verdicts included, one thread.\n";
  md += summary_markdown(score);
  for (const auto& fam : score["families"]) {
    const std::string name = fam["name"].get<std::string>();
    md += fmt::format("\n## {}\n\n{} trace(s)", name, fam["traces"].get<int64_t>());
    if (!fam["generator"].get<std::string>().empty())
      md += fmt::format(", generated by `{}`", fam["generator"].get<std::string>());
    md += ".\n\n| method | tester | kind | rays | correct /M | self_hit /M | false_hit /M | missed /M "
          "| suspect % | rejected % | rays/s |\n|---|---|---|---:|---|---|---|---|---:|---:|---:|\n";
    for (const auto& r : score["rows"]) {
      if (r["family"] != name) continue;
      const auto& pm = r["per_million"];
      md += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                        r["method"].get<std::string>(), r["tester"].get<std::string>(),
                        r["kind"].get<std::string>(), r["rays"].get<uint64_t>(), rate_cell(pm["correct"]),
                        rate_cell(pm["self_hit"]), rate_cell(pm["false_hit"]), rate_cell(pm["missed"]),
                        percent(r["avoidance"]["suspect_rate"].get<double>()),
                        percent(r["avoidance"]["rejection_rate"].get<double>()),
                        r.contains("rays_per_s") ? fmt::format("{:.0f}", r["rays_per_s"].get<double>()) : "");
    }
  }
  return md;
}

}  // namespace vbsim
