#include "score/tradeoff_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "score/score_table.h"

namespace vbsim {

namespace {

using Key = std::tuple<std::string, std::string, std::string>;  // family, method, tester

Key key_of(const nlohmann::json& r) {
  return {r["family"].get<std::string>(), r["method"].get<std::string>(), r["tester"].get<std::string>()};
}

std::string per_million_cell(double rate, double lower, double upper) {
  return fmt::format("{} [{}, {}]", format_per_million(rate), format_per_million(lower), format_per_million(upper));
}

}  // namespace

std::vector<TradeoffRow> tradeoff_rows(const nlohmann::json& score) {
  std::vector<TradeoffRow> out;
  std::map<Key, size_t> index;
  const auto row_for = [&](const nlohmann::json& r) -> TradeoffRow& {
    const Key k = key_of(r);
    auto it = index.find(k);
    if (it == index.end()) {
      it = index.emplace(k, out.size()).first;
      out.emplace_back();
      std::tie(out.back().family, out.back().method, out.back().tester) = k;
    }
    return out[it->second];
  };
  for (const auto& r : score["rows"]) {
    TradeoffRow& t = row_for(r);
    const std::string kind = r["kind"].get<std::string>();
    if (kind == "all") {
      t.bits_per_ray = r["config"]["bits_per_ray"].get<int>();
      t.ops_per_ray = r.value("ops_per_ray", 0.0);
      t.rays_per_s = r.value("rays_per_s", 0.0);
      if (r.contains("energy")) {
        t.energy_per_ray_pj = r["energy"]["per_ray_pj"].get<double>();
        t.method_energy_per_ray_pj = r["energy"]["method_per_ray_pj"].get<double>();
      }
      if (r.contains("cycle")) {
        t.has_cycles = true;
        t.cycles_per_ray = r["cycle"]["cycles_per_ray"].get<double>();
        t.rays_per_cycle = r["cycle"]["rays_per_cycle"].get<double>();
        t.cycle_preset = r["cycle"]["preset"].get<std::string>();
        if (r["cycle"].contains("energy_per_ray_pj")) {
          t.has_cycle_energy = true;
          t.cycle_energy_per_ray_pj = r["cycle"]["energy_per_ray_pj"].get<double>();
          t.chip_mm2 = r["cycle"]["chip_mm2"].get<double>();
        }
      }
    } else if (kind == kSecondaryKind) {
      t.secondary_scored = r["scored"].get<uint64_t>();
      t.secondary_errors = r["errors"]["count"].get<uint64_t>();
      const auto& pm = r["errors"]["per_million"];
      t.secondary_rate = pm["rate"].get<double>();
      t.secondary_lower = pm["lower"].get<double>();
      t.secondary_upper = pm["upper"].get<double>();
      t.offset_fallbacks = r.value("offset_fallbacks", uint64_t{0});
    } else if (kind == "primary") {
      t.camera_scored = r["scored"].get<uint64_t>();
      t.camera_misses = r["counts"]["missed"].get<uint64_t>();
      t.camera_miss_rate = r["per_million"]["missed"]["rate"].get<double>();
      t.camera_lower = r["per_million"]["missed"]["lower"].get<double>();
      t.camera_upper = r["per_million"]["missed"]["upper"].get<double>();
    }
  }
  return out;
}

std::string tradeoff_markdown(const std::vector<TradeoffRow>& rows) {
  const bool cycles = std::any_of(rows.begin(), rows.end(), [](const TradeoffRow& r) { return r.has_cycles; });
  std::string md =
      "| method | tester | secondary errors /M [95%] | secondary rays | camera misses /M [95%] | bits/ray | ops/ray | "
      "pJ/ray (ops) | method pJ/ray |";
  md += cycles ? " cycles/ray | rays/cycle |" : "";
  md += " rays/s |\n|---|---|---|---:|---:|---:|---:|---:|---:|";
  md += cycles ? "---:|---:|" : "";
  md += "---:|\n";
  for (const TradeoffRow& r : rows) {
    md += fmt::format("| `{}` | {} | {} | {} | {} | {} | {:.3g} | {:.4g} | {:.3g} |", r.method, r.tester,
                      per_million_cell(r.secondary_rate, r.secondary_lower, r.secondary_upper), r.secondary_scored,
                      per_million_cell(r.camera_miss_rate, r.camera_lower, r.camera_upper), r.bits_per_ray,
                      r.ops_per_ray, r.energy_per_ray_pj, r.method_energy_per_ray_pj);
    if (cycles)
      md += r.has_cycles ? fmt::format(" {:.3g} | {:.4g} |", r.cycles_per_ray, r.rays_per_cycle) : "  |  |";
    md += fmt::format(" {:.0f} |\n", r.rays_per_s);
  }
  return md;
}

std::string tradeoff_text(const std::vector<TradeoffRow>& rows) {
  size_t width = 6;
  for (const TradeoffRow& r : rows) width = std::max(width, r.method.size());
  std::string preset = "small";
  for (const TradeoffRow& r : rows)
    if (r.has_cycles) preset = r.cycle_preset;
  std::string s = fmt::format("{:<{}}  {:<16}  {:>24}  {:>14}  {:>20}  {:>13}  {:>8}  {:>8}\n", "method", width,
                              "tester", "secondary err/M [95%]", "camera misses", "camera /M [95%]",
                              fmt::format("cycles/ray {}", preset), "bits/ray", "pJ/ray");
  for (const TradeoffRow& r : rows)
    s += fmt::format("{:<{}}  {:<16}  {:>24}  {:>14}  {:>20}  {:>13}  {:>8}  {:>8.4g}\n", r.method, width, r.tester,
                     per_million_cell(r.secondary_rate, r.secondary_lower, r.secondary_upper),
                     fmt::format("{} of {}", r.camera_misses, r.camera_scored),
                     per_million_cell(r.camera_miss_rate, r.camera_lower, r.camera_upper),
                     r.has_cycles ? fmt::format("{:.2f}", r.cycles_per_ray) : "-", r.bits_per_ray,
                     r.energy_per_ray_pj);
  return s;
}

}  // namespace vbsim
