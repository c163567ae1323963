#include "fit/fit_report.h"

#include <fmt/format.h>

namespace vbsim {

namespace {

std::string ray_text(const FitRay& ray) { return fmt::format("{} ray {} ({})", ray.trace, ray.id, ray.kind); }

nlohmann::json ray_json(const FitRay& ray) {
  if (ray.trace.empty()) return nullptr;
  return {{"trace", ray.trace}, {"id", ray.id}, {"kind", ray.kind}};
}

std::string num(double v) { return fmt::format("{:.6g}", v); }

}  // namespace

std::string fit_text(const FitResult& r) {
  std::string s = fmt::format("{}: {} ({} scored rays, searched 0 and {} .. {}", r.key, r.description, r.rays,
                              num(r.searched_low), num(r.searched_high));
  s += r.resolution > 0 ? fmt::format(", grid step {:.2g}%)\n", 100 * r.resolution) : ", integers)\n";
  if (r.missed_at_zero) s += fmt::format("  none exists: {} is missed even at 0\n", ray_text(r.needs_at_most));
  if (r.self_hit_at_top)
    s += fmt::format("  none exists in the searched range: {} self-hits even at {}\n", ray_text(r.needs_at_least),
                     num(r.searched_high));
  if (r.missed_at_zero || r.self_hit_at_top) return s;
  if (!r.feasible && !r.checked) {
    s += fmt::format("  none exists: {} self-hits at {} and below (needs more); {} is missed at {} and above (needs less)",
                     ray_text(r.needs_at_least), num(r.below), ray_text(r.needs_at_most), num(r.above));
    s += r.above <= r.below ? fmt::format("; {} <= {}\n", num(r.above), num(r.below))
                            : fmt::format("; no grid value lies between them (grid step {:.2g}%)\n", 100 * r.resolution);
    return s;
  }
  if (r.needs_at_least.trace.empty())
    s += "  lower end: 0 (no ray self-hits at 0)\n";
  else
    s += fmt::format("  lower end: {} ({} self-hits at {}, one grid step below)\n", num(r.lowest),
                     ray_text(r.needs_at_least), num(r.below));
  if (r.needs_at_most.trace.empty())
    s += fmt::format("  upper end: beyond {} (no ray is missed in the searched range)\n", num(r.highest));
  else
    s += fmt::format("  upper end: {} ({} is missed at {}, one grid step above)\n", num(r.highest), ray_text(r.needs_at_most), num(r.above));
  if (!r.check_failures.empty()) {
    s += fmt::format("  not monotone: at {} these rays still fail:", num(r.lowest));
    for (const FitRay& f : r.check_failures) s += " " + ray_text(f) + ";";
    s += r.repaired_index >= 0
             ? fmt::format("\n  the smallest grid value above it at which every ray passes:\n")
             : fmt::format("\n  none exists on the grid: at every value from {} to {} one of these rays fails; "
                           "below, the first ray self-hits; above, the second is missed\n",
                           num(r.lowest), num(r.highest));
  }
  const double answer = r.repaired_index >= 0 ? r.repaired : r.lowest;
  if (r.feasible) s += fmt::format("  smallest: {}\n", num(answer));
  s += fmt::format("  check at {}: {} self_hit, {} missed, {} false_hit", num(answer), r.check_self_hit,
                   r.check_missed, r.check_false_hit);
  if (r.lowest_index > 0) s += fmt::format("; at {}: {} self_hit", num(r.below), r.below_self_hit);
  s += "\n";
  return s;
}

nlohmann::json fit_json(const FitResult& r) {
  nlohmann::json j = {{"key", r.key},
                      {"description", r.description},
                      {"rays", r.rays},
                      {"searched", {r.searched_low, r.searched_high}},
                      {"grid_step", r.resolution},
                      {"feasible", r.feasible}};
  j["self_hit_at_top"] = r.self_hit_at_top;
  j["missed_at_zero"] = r.missed_at_zero;
  j["smallest"] = {{"value", r.self_hit_at_top ? nlohmann::json(nullptr) : nlohmann::json(r.lowest)}, {"below", r.below}, {"ray", ray_json(r.needs_at_least)}};
  j["largest"] = {{"value", r.missed_at_zero ? nlohmann::json(nullptr) : nlohmann::json(r.highest)},
                  {"above", r.above},
                  {"ray", ray_json(r.needs_at_most)}};
  if (r.checked) {
    nlohmann::json failures = nlohmann::json::array();
    for (const FitRay& f : r.check_failures) failures.push_back(ray_json(f));
    j["check"] = {{"value", r.repaired_index >= 0 ? r.repaired : r.lowest},
                  {"repaired", r.repaired_index >= 0},
                  {"self_hit", r.check_self_hit},
                  {"missed", r.check_missed},
                  {"false_hit", r.check_false_hit},
                  {"below", r.below},
                  {"below_self_hit", r.below_self_hit},
                  {"passed", r.check_self_hit == 0 && r.check_missed == 0},
                  {"failures_at_smallest", failures}};
  }
  return j;
}

}  // namespace vbsim
