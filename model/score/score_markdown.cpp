#include "score/score_markdown.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <vector>

#include "score/score_table.h"
#include "score/tradeoff_table.h"

namespace vbsim {

namespace {

std::string rate_cell(const nlohmann::json& r) {
  return fmt::format("{} [{}, {}]", format_per_million(r["rate"].get<double>()),
                     format_per_million(r["lower"].get<double>()), format_per_million(r["upper"].get<double>()));
}

/// A per-million rate with its 95% interval: "rate [lower, upper]".
std::string interval_cell(double rate, double lower, double upper) {
  return fmt::format("{} [{}, {}]", format_per_million(rate), format_per_million(lower), format_per_million(upper));
}

std::string percent(double x) { return x == 0 ? "0" : fmt::format("{:.3f}", 100 * x); }

void add_unique(std::vector<std::string>& v, const std::string& x) {
  if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
}

/// Methods down, families across; `cell` gives a row's entry ("" when absent).
std::string grid(const std::vector<std::string>& methods, const std::vector<std::string>& families,
                 const std::vector<TradeoffRow>& rows, const std::string& tester,
                 const std::function<std::string(const TradeoffRow&)>& cell) {
  std::string md = "| method |";
  for (const std::string& f : families) md += fmt::format(" {} |", f);
  md += "\n|---|";
  for (size_t i = 0; i < families.size(); ++i) md += "---:|";
  md += "\n";
  for (const std::string& m : methods) {
    md += fmt::format("| `{}` |", m);
    for (const std::string& f : families) {
      std::string c = " ";
      for (const TradeoffRow& r : rows)
        if (r.method == m && r.family == f && r.tester == tester) c = cell(r);
      md += fmt::format(" {} |", c);
    }
    md += "\n";
  }
  return md;
}

std::string summaries(const std::vector<TradeoffRow>& rows, const std::vector<std::string>& families) {
  std::vector<std::string> methods, testers;
  for (const TradeoffRow& r : rows) {
    add_unique(methods, r.method);
    add_unique(testers, r.tester);
  }
  std::string md;
  for (const std::string& tester : testers) {
    md += fmt::format("\n## Summary, {} tester: secondary-ray errors per million\n\n", tester);
    md += "self_hit + false_hit + missed per million scored secondary rays (every ray that leaves a surface: "
          "reflection, refraction, diffuse and shadow rays), with its 95% Wilson interval. This is each "
          "method's headline figure.\n\n";
    md += grid(methods, families, rows, tester, [](const TradeoffRow& r) {
      return interval_cell(r.secondary_rate, r.secondary_lower, r.secondary_upper);
    });
    const bool misses = std::any_of(rows.begin(), rows.end(), [&](const TradeoffRow& r) {
      return r.tester == tester && r.camera_misses > 0;
    });
    if (misses) {
      md += fmt::format("\n### Camera rays the {} tester missed, per million camera rays\n\n", tester);
      md += "Camera rays whose exact answer is a hit and that this tester reported as a miss (for a "
            "conservative tester, the price of its bound); no method acts on camera rays but `tmin`.\n\n";
      md += grid(methods, families, rows, tester, [](const TradeoffRow& r) {
        return interval_cell(r.camera_miss_rate, r.camera_lower, r.camera_upper);
      });
    }
    md += fmt::format("\n### The method's energy per ray, pJ, {} tester\n\n", tester);
    md += "The operations the method adds (emission, result, candidate and suspect tests) and its extra "
          "ray-record bits, priced by the technology file (`docs/energy.md`), per ray of the family; no "
          "memory, no leakage.\n\n";
    md += grid(methods, families, rows, tester,
               [](const TradeoffRow& r) { return fmt::format("{:.3g}", r.method_energy_per_ray_pj); });
    const auto cycled = std::find_if(rows.begin(), rows.end(),
                                     [&](const TradeoffRow& r) { return r.tester == tester && r.has_cycles; });
    if (cycled != rows.end()) {
      md += fmt::format("\n### Cycles per ray, {} preset, {} tester\n\n", cycled->cycle_preset, tester);
      md += "The cycle-level model on the same traces in the same run: simulated cycles of every trace "
            "(each replayed on its own) over its rays.\n\n";
      md += grid(methods, families, rows, tester, [](const TradeoffRow& r) {
        return r.has_cycles ? fmt::format("{:.3g}", r.cycles_per_ray) : std::string();
      });
    }
  }
  return md;
}

/// The verdicts of one family: camera rays, the secondary sum, then each secondary kind.
std::string kind_table(const nlohmann::json& score, const std::string& family) {
  std::string md = "| method | tester | kind | rays | correct /M | self_hit /M | false_hit /M | missed /M "
                   "| suspect % | rejected % |\n|---|---|---|---:|---|---|---|---|---:|---:|\n";
  for (const auto& r : score["rows"]) {
    if (r["family"] != family || r["kind"] == "all") continue;
    const auto& pm = r["per_million"];
    md += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r["method"].get<std::string>(),
                      r["tester"].get<std::string>(), r["kind"].get<std::string>(), r["rays"].get<uint64_t>(),
                      rate_cell(pm["correct"]), rate_cell(pm["self_hit"]), rate_cell(pm["false_hit"]),
                      rate_cell(pm["missed"]), percent(r["avoidance"]["suspect_rate"].get<double>()),
                      percent(r["avoidance"]["rejection_rate"].get<double>()));
  }
  return md;
}

}  // namespace

std::string score_markdown(const nlohmann::json& score, const std::string& regenerate) {
  std::string md = "# Accuracy of every method\n\n";
  md += "Generated by `vbsim score`; do not edit by hand. Regenerate with:\n\n";
  md += fmt::format("    {}\n\n", regenerate);
  md += fmt::format("The command that scored the traces:\n\n    {}\n\n", score["command"].get<std::string>());
  md += "Camera rays (kind `primary`) and secondary rays (every ray that leaves a surface, the rays "
        "self-intersection is about) are reported apart; a method's headline figure is its secondary-ray "
        "error rate. Rates are per million scored rays (rays with `expect`) with the 95% Wilson score "
        "interval in brackets; a zero count still has a non-zero upper bound. Per family, the trade-off "
        "table puts each method and tester's secondary errors next to the camera rays its tester missed, "
        "its bits per ray in flight, its operations per ray (`docs/methods.md`, with the candidates and "
        "suspects the family really produces), the operations' energy per ray (all of them, and the "
        "method's own; `docs/energy.md`), the cycle-level model's cycles per ray and rays per cycle "
        "(when measured) and its functional replay speed (rays/s, one thread, verdicts included). "
        "`suspect %` and `rejected %` are the avoidance unit's suspects and the filters' rejections per "
        "candidate hit.\n";
  std::vector<std::string> families;
  for (const auto& f : score["families"]) families.push_back(f["name"].get<std::string>());
  const std::vector<TradeoffRow> rows = tradeoff_rows(score);
  md += summaries(rows, families);
  for (const auto& fam : score["families"]) {
    const std::string name = fam["name"].get<std::string>();
    md += fmt::format("\n## {}\n\n{} trace(s)", name, fam["traces"].get<int64_t>());
    if (!fam["generator"].get<std::string>().empty())
      md += fmt::format(", generated by `{}`", fam["generator"].get<std::string>());
    md += ".\n\n";
    std::vector<TradeoffRow> mine;
    for (const TradeoffRow& r : rows)
      if (r.family == name) mine.push_back(r);
    md += tradeoff_markdown(mine) + "\n" + kind_table(score, name);
  }
  return md;
}

}  // namespace vbsim
