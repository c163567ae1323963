#include "hw/observe/hw_stats.h"

#include <fmt/format.h>

namespace vbsim::hw {

namespace {

double per(double num, double den) { return den > 0 ? num / den : 0.0; }

/// Fraction of the issue slots of all `u` pipelines of all groups of cores that were used.
double utilisation(const UnitCounters& c, const UnitConfig& u, const HwConfig& cfg, uint64_t cycles) {
  const double busy = c.busy_cycles ? static_cast<double>(c.busy_cycles) : static_cast<double>(c.ops) * u.issue_interval;
  return per(busy, static_cast<double>(cycles) * u.count * unit_groups(u, cfg.cores));
}

/// The utilisation, or null for a replaced unit (its pipelines are its own).
nlohmann::json utilisation_json(const UnitCounters& c, const UnitConfig& u, const HwConfig& cfg, uint64_t cycles) {
  return c.replaced ? nlohmann::json(nullptr) : nlohmann::json(utilisation(c, u, cfg, cycles));
}

/// A utilisation in the table: a percentage, or "n/a" for a replaced unit.
std::string utilisation_text(const UnitCounters& c, const UnitConfig& u, const HwConfig& cfg, uint64_t cycles) {
  return c.replaced ? std::string("  n/a ") : fmt::format("{:5.1f}%", 100 * utilisation(c, u, cfg, cycles));
}

nlohmann::json unit_json(const UnitCounters& c, const UnitConfig& u, const HwConfig& cfg, uint64_t cycles,
                         uint64_t rays) {
  nlohmann::json j = {{"ops", c.ops},
                      {"ops_per_ray", per(c.ops, rays)},
                      {"pipeline_full_cycles", c.wait_cycles},
                      {"utilisation", utilisation_json(c, u, cfg, cycles)}};
  if (c.replaced) j["replaced"] = true;
  return j;
}

}  // namespace

nlohmann::json hw_stats_json(const HwReport& r) {
  const HwCounters& c = r.counters;
  const HwConfig& cfg = r.config;
  const uint64_t slots = uint64_t{cfg.cores} * cfg.slots_per_core;
  nlohmann::json j;
  j["cycles"] = c.cycles;
  j["rays"] = c.rays;
  j["rays_per_cycle"] = per(c.rays, c.cycles);
  j["clock_mhz"] = cfg.clock_mhz;
  j["rays_per_s"] = per(c.rays, c.cycles) * cfg.clock_mhz * 1e6;
  j["units"] = {{"box", unit_json(c.box, cfg.box, cfg, c.cycles, c.rays)},
                {"triangle", unit_json(c.triangle, cfg.triangle, cfg, c.cycles, c.rays)},
                {"avoidance", unit_json(c.avoidance, cfg.avoidance, cfg, c.cycles, c.rays)}};
  if (cfg.controller.count > 0) {
    const UnitConfig ctrl{cfg.controller.count, cfg.controller.latency, cfg.controller.issue_interval};
    j["units"]["controller"] = unit_json(c.controller, ctrl, cfg, c.cycles, c.rays);
  }
  if (cfg.box_low.count > 0) j["units"]["box_low"] = unit_json(c.box_low, cfg.box_low, cfg, c.cycles, c.rays);
  j["utilisation"] = {{"box", utilisation_json(c.box, cfg.box, cfg, c.cycles)},
                      {"triangle", utilisation_json(c.triangle, cfg.triangle, cfg, c.cycles)},
                      {"avoidance", utilisation_json(c.avoidance, cfg.avoidance, cfg, c.cycles)},
                      {"slots", per(c.slot_cycles, static_cast<double>(c.cycles) * slots)},
                      {"source", per(c.source_busy_cycles, c.cycles)}};
  // Waits in slot-cycles (summed over rays), and their share of all slot-cycles.
  nlohmann::json waits = {{"memory_wait", c.memory_wait_cycles},
                                {"box_pipeline_full", c.box.wait_cycles},
                                {"triangle_pipeline_full", c.triangle.wait_cycles},
                                {"avoidance_pipeline_full", c.avoidance.wait_cycles},
                                {"stack_refill_wait", c.refill_wait_cycles}};
  if (cfg.controller.count > 0) waits["controller_full"] = c.controller.wait_cycles;
  if (cfg.box_low.count > 0) {
    j["utilisation"]["box_low"] = utilisation_json(c.box_low, cfg.box_low, cfg, c.cycles);
    waits["box_low_pipeline_full"] = c.box_low.wait_cycles;
  }
  nlohmann::json shares;
  for (const auto& [k, v] : waits.items()) shares[k] = per(v.get<double>(), c.slot_cycles);
  j["stalls"] = {{"slot_cycles", waits},
                 {"share_of_slot_cycles", shares},
                 {"no_free_slot_cycles", c.no_free_slot_cycles},
                 {"stack_overflow", {{"spills", c.spills}, {"refills", c.refill_reads}}}};
  j["memory"] = {{"port", r.memory},
                 {"node_fetches", c.node_fetches},
                 {"leaf_fetches", c.leaf_fetches},
                 {"refill_reads", c.refill_reads}};
  nlohmann::json kinds = nlohmann::json::object();
  for (int k = 0; k < kRayKindCount; ++k) {
    const KindStats& ks = r.replay.by_kind[k];
    if (ks.rays == 0) continue;
    const CandidateCounters& cc = ks.candidates;
    kinds[ray_kind_name(static_cast<RayKind>(k))] = {{"rays", ks.rays},
                                                     {"candidates", cc.candidates},
                                                     {"suspects", cc.suspects},
                                                     {"unit_ops", c.avoidance_ops_by_kind[k]},
                                                     {"rejected", cc.rejected},
                                                     {"suspect_rate", per(cc.suspects, cc.candidates)},
                                                     {"rejection_rate", per(cc.rejected, cc.candidates)}};
  }
  j["avoidance"] = {{"unit_ops", c.avoidance.ops}, {"by_kind", kinds}};
  j["source"] = {{"busy_cycles", c.source_busy_cycles},
                 {"sign_bits_computed", c.sign_bits_computed},
                 {"emission_ops", c.emission_ops},
                 {"emission_op_cycles",
                  cfg.source.emission_width ? 0 : c.emission_ops * cfg.source.emission_op_cycles}};
  if (cfg.source.emission_width)
    j["source"]["emission_unit"] = {{"width", cfg.source.emission_width},
                                    {"depth", cfg.source.emission_depth},
                                    {"ops", c.emission_unit_ops}};
  if (c.source_replaced) {  // a replacement source: its counts are its own
    j["source"] = {{"replaced", true}};
    j["utilisation"]["source"] = nullptr;
  }
  j["latency"] = {{"min", c.latency_min},
                  {"mean", per(c.slot_cycles, c.rays)},
                  {"max", c.latency_max},
                  {"bucket_cycles", cfg.latency_bucket_cycles},
                  {"histogram", c.latency_histogram}};
  j["systemc"] = {{"start_ps", r.systemc.start_ps},
                  {"end_ps", r.systemc.end_ps},
                  {"period_ps", r.systemc.period_ps},
                  {"cycles", r.systemc.cycles},
                  {"activations", r.systemc.activations}};
  return j;
}

std::string hw_summary_table(const HwReport& r) {
  const HwCounters& c = r.counters;
  const HwConfig& cfg = r.config;
  std::string s = fmt::format("hw ({} preset, {} cores x {} slots, {:.0f} MHz, memory {})\n", cfg.preset, cfg.cores,
                              cfg.slots_per_core, cfg.clock_mhz, cfg.memory.ideal ? "ideal" : cfg.memory.objects.enabled ? "object caches" : "hierarchy");
  s += fmt::format("  cycles {:>12}   rays/cycle {:>8.4f}   rays/s at clock {:>12.4g}\n", c.cycles,
                   per(c.rays, c.cycles), per(c.rays, c.cycles) * cfg.clock_mhz * 1e6);
  s += fmt::format("  utilisation  box {}  triangle {}  avoidance {}  slots {:5.1f}%\n",
                   utilisation_text(c.box, cfg.box, cfg, c.cycles),
                   utilisation_text(c.triangle, cfg.triangle, cfg, c.cycles),
                   utilisation_text(c.avoidance, cfg.avoidance, cfg, c.cycles),
                   100 * per(c.slot_cycles, static_cast<double>(c.cycles) * cfg.cores * cfg.slots_per_core));
  s += fmt::format("  waits (share of slot-cycles)  memory {:.1f}%  box full {:.1f}%  triangle full {:.1f}%  "
                   "avoidance full {:.1f}%  stack refill {:.1f}%\n",
                   100 * per(c.memory_wait_cycles, c.slot_cycles), 100 * per(c.box.wait_cycles, c.slot_cycles),
                   100 * per(c.triangle.wait_cycles, c.slot_cycles), 100 * per(c.avoidance.wait_cycles, c.slot_cycles),
                   100 * per(c.refill_wait_cycles, c.slot_cycles));
  if (cfg.box_low.count > 0)
    s += fmt::format("  low-precision box pool: {} operations, utilisation {}, box full {:.1f}%\n", c.box_low.ops,
                     utilisation_text(c.box_low, cfg.box_low, cfg, c.cycles),
                     100 * per(c.box_low.wait_cycles, c.slot_cycles));
  s += fmt::format("  source held a ray for want of a slot: {} cycles   stack spills {}  refills {}\n",
                   c.no_free_slot_cycles, c.spills, c.refill_reads);
  s += fmt::format("  ray latency (cycles)  min {}  mean {:.1f}  max {}\n", c.latency_min, per(c.slot_cycles, c.rays),
                   c.latency_max);
  return s;
}

}  // namespace vbsim::hw
