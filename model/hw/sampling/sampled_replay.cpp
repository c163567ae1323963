#include "hw/sampling/sampled_replay.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "hw/sampling/sample_estimator.h"
#include "hw/sampling/sampled_feed.h"

namespace vbsim::hw {

namespace {

nlohmann::json interval_json(double low, double high) { return nlohmann::json::array({low, high}); }

/// A number for JSON: an infinite half-width (fewer than 2 units) is null.
nlohmann::json finite(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

CycleRunResult run_sampled_cycle_replay(const RayFeed& feed, const Scene& scene, const Bvh& bvh,
                                        const ReplayOptions& opt, const HwConfig& cfg, const RayResultSink& sink,
                                        const CycleRunOptions& options, const SamplingConfig& sampling) {
  check_sampling_config(sampling);
  const AcceleratorUnits& u = options.units;
  if (u.box_unit || u.triangle_tester || u.avoidance_unit || u.l1_cache || u.dispatcher || u.l2_cache ||
      u.result_sink || u.ray_source || u.external_memory)
    throw std::invalid_argument("sampling: replaced units are not supported (fast-forwarding uses the built-in ones)");
  SampledFeed sampled(sampling, feed, sink);
  CycleRunOptions run = options;
  run.sampled = &sampled;
  CycleRunResult r = run_cycle_replay(feed, scene, bvh, opt, cfg, sink, run);
  if (r.stats.partial) return r;  // a stopped run: the detailed figures as they were

  // The estimates (docs/sampling.md).
  const double population = static_cast<double>(sampled.rays());
  std::vector<UnitMeasure> cycles, l1, l2;
  for (const MeasuredUnit* u : sampled.complete_units()) {
    cycles.push_back({static_cast<double>(u->end_cycle - u->start_cycle), static_cast<double>(u->rays)});
    l1.push_back({static_cast<double>(u->end.l1_hits - u->start.l1_hits),
                  static_cast<double>(u->end.l1_accesses - u->start.l1_accesses)});
    l2.push_back({static_cast<double>(u->end.l2_hits - u->start.l2_hits),
                  static_cast<double>(u->end.l2_accesses - u->start.l2_accesses)});
  }
  const double conf = sampling.confidence;
  // The head and tail strata, measured whole; the body, estimated.
  double strata_cycles = 0, strata_rays = 0;
  nlohmann::json strata = nlohmann::json::object();
  for (const auto& [name, which] : {std::pair<const char*, MeasuredUnit::Stratum>{"head", MeasuredUnit::Stratum::Head},
                                    {"tail", MeasuredUnit::Stratum::Tail}})
    if (const MeasuredUnit* u = sampled.stratum(which)) {
      strata_cycles += static_cast<double>(u->end_cycle - u->start_cycle);
      strata_rays += static_cast<double>(u->rays);
      strata[name] = {{"trace_start", u->trace_start}, {"rays", u->rays}, {"cycles", u->end_cycle - u->start_cycle}};
    }
  const double body = population - strata_rays;
  const RatioEstimate cpr_body = ratio_estimate(cycles, conf, body);
  const bool body_measured = !cycles.empty() || body <= 0;
  const double body_cycles = body > 0 ? cpr_body.ratio * body : 0;
  const double body_half = body > 0 ? cpr_body.half_width * body : 0;
  const double total = strata_cycles + body_cycles;
  const double total_lo = std::max(0.0, total - body_half), total_hi = total + body_half;
  // Cycles per ray over the whole trace, its interval from the total's.
  RatioEstimate cpr;
  cpr.units = cpr_body.units;
  cpr.ratio = population > 0 ? total / population : 0;
  cpr.half_width = population > 0 ? body_half / population : 0;
  if (!body_measured) cpr.half_width = std::numeric_limits<double>::infinity();
  const double rpc = cpr.ratio > 0 ? 1 / cpr.ratio : 0;
  const double rpc_lo = cpr.high() > 0 && std::isfinite(cpr.high()) ? 1 / cpr.high() : 0;
  const double rpc_hi = cpr.low() > 0 ? 1 / cpr.low() : std::numeric_limits<double>::infinity();

  nlohmann::json& hw = r.hw;
  const uint64_t detailed_cycles = hw.value("cycles", uint64_t{0});
  const uint64_t detailed_rays = hw.value("rays", uint64_t{0});
  hw["cycles"] = static_cast<uint64_t>(std::llround(total));
  hw["rays"] = sampled.rays();
  hw["rays_per_cycle"] = rpc;
  hw["rays_per_s"] = rpc * cfg.clock_mhz * 1e6;
  nlohmann::json s;
  s["estimated"] = {"cycles", "rays_per_cycle", "rays_per_s"};
  s["note"] =
      "hw.cycles, hw.rays_per_cycle and hw.rays_per_s are estimates for the whole trace (hw.rays is exact); every "
      "other hw figure describes only the rays simulated in detail (hw.sampling.detailed)";
  s["parameters"] = sampling_config_json(sampling);
  s["confidence"] = conf;
  s["rays"] = sampled.rays();
  s["rays_fast_forwarded"] = sampled.fast_forwarded();
  s["units_measured"] = cycles.size();
  uint64_t drained = 0;  // the last body unit, when it ends in the drain
  for (const MeasuredUnit& u : sampled.units()) drained += u.drained;
  s["units_left_out"] = drained;
  uint64_t measured_rays = 0;
  for (const MeasuredUnit* u : sampled.complete_units()) measured_rays += u->rays;
  s["rays_measured"] = measured_rays;
  s["measuring_ended"] = sampled.stop_reason();
  s["detailed"] = {{"rays", detailed_rays}, {"cycles", detailed_cycles}};
  s["strata"] = strata;  // measured whole: their cycles are exact
  s["body"] = {{"rays", body}, {"cycles_estimate", body_cycles}, {"cycles_per_ray", cpr_body.ratio}};
  nlohmann::json units = nlohmann::json::array();  // each measured unit: what its two instants saw
  for (const MeasuredUnit* u : sampled.complete_units())
    units.push_back({{"trace_start", u->trace_start},
                     {"rays", u->rays},
                     {"cycles", u->end_cycle - u->start_cycle},
                     {"start_cycle", u->start_cycle},
                     {"l1_hits", u->end.l1_hits - u->start.l1_hits},
                     {"l1_accesses", u->end.l1_accesses - u->start.l1_accesses},
                     {"l2_hits", u->end.l2_hits - u->start.l2_hits},
                     {"l2_accesses", u->end.l2_accesses - u->start.l2_accesses}});
  s["units"] = std::move(units);
  nlohmann::json est, iv, rel;
  est["cycles"] = total;
  iv["cycles"] = std::isfinite(total_hi) ? interval_json(total_lo, total_hi) : nlohmann::json();
  rel["cycles"] = finite(cpr.relative());
  est["cycles_per_ray"] = cpr.ratio;
  iv["cycles_per_ray"] =
      std::isfinite(cpr.half_width) ? interval_json(std::max(0.0, cpr.low()), cpr.high()) : nlohmann::json();
  est["rays_per_cycle"] = rpc;
  iv["rays_per_cycle"] = std::isfinite(cpr.half_width) ? interval_json(rpc_lo, rpc_hi) : nlohmann::json();
  // Hit rates over the trace: the strata's hits and accesses, exact, and the
  // body's, its accesses per ray times its rays and the units' hit rate; the
  // interval from the body hit rate's (the body's accesses taken as exact).
  double rays_measured = 0;
  for (const UnitMeasure& u : cycles) rays_measured += u.x;
  for (const bool l1_level : {true, false}) {
    const std::vector<UnitMeasure>& m = l1_level ? l1 : l2;
    const char* name = l1_level ? "l1_hit_rate" : "l2_hit_rate";
    double strata_hits = 0, strata_accesses = 0, accesses = 0;
    for (const UnitMeasure& u : m) accesses += u.x;
    for (const MeasuredUnit::Stratum which : {MeasuredUnit::Stratum::Head, MeasuredUnit::Stratum::Tail})
      if (const MeasuredUnit* u = sampled.stratum(which)) {
        strata_hits += static_cast<double>(l1_level ? u->end.l1_hits - u->start.l1_hits : u->end.l2_hits - u->start.l2_hits);
        strata_accesses += static_cast<double>(l1_level ? u->end.l1_accesses - u->start.l1_accesses
                                                        : u->end.l2_accesses - u->start.l2_accesses);
      }
    if (accesses == 0 && strata_accesses == 0) continue;  // no built-in cache
    const RatioEstimate e = ratio_estimate(m, conf, 0);
    const double body_accesses = rays_measured > 0 && body > 0 ? accesses / rays_measured * body : 0;
    const double all = strata_accesses + body_accesses;
    auto rate = [&](double body_rate) { return (strata_hits + body_accesses * body_rate) / all; };
    est[name] = rate(e.ratio);
    const bool known = std::isfinite(e.half_width) || body_accesses == 0;
    const double half = body_accesses > 0 ? e.half_width : 0;
    iv[name] = known ? interval_json(rate(e.ratio - half), rate(e.ratio + half)) : nlohmann::json();
    rel[name] = known ? finite((rate(e.ratio + half) - rate(e.ratio)) / rate(e.ratio)) : nlohmann::json();
  }
  s["estimates"] = est;
  s["intervals"] = iv;
  s["relative_half_width"] = rel;
  hw["sampling"] = s;

  const std::string pct = std::isfinite(cpr.relative()) ? fmt::format("+-{:.2f}%", 100 * cpr.relative()) : "no interval";
  std::string head = fmt::format(
      "sampled (ESTIMATES, {:.0f}% confidence intervals): cycles {:.0f} [{:.0f}, {:.0f}] ({}), rays/cycle {:.4f}, "
      "cycles/ray {:.3f}",
      100 * conf, total, total_lo, std::isfinite(total_hi) ? total_hi : 0.0, pct, rpc, cpr.ratio);
  if (est.contains("l1_hit_rate")) head += fmt::format(", L1 hit rate {:.4f}", est["l1_hit_rate"].get<double>());
  if (est.contains("l2_hit_rate")) head += fmt::format(", L2 hit rate {:.4f}", est["l2_hit_rate"].get<double>());
  head += fmt::format(
      "\n  from the first {} and last {} rays measured whole and {} units of {} rays (one every {}, {} warm-up rays "
      "before each), {} of {} rays simulated in detail, "
      "{} fast-forwarded; measuring ended: {}\n  the hw figures below describe only the {} rays simulated in detail "
      "({} cycles)\n",
      strata.contains("head") ? strata["head"]["rays"].get<uint64_t>() : 0,
      strata.contains("tail") ? strata["tail"]["rays"].get<uint64_t>() : 0, cycles.size(), sampling.unit,
      sampling.interval, sampling.warmup, detailed_rays, sampled.rays(),
      sampled.fast_forwarded(), sampled.stop_reason(), detailed_rays, detailed_cycles);
  r.table = head + r.table;
  return r;
}

}  // namespace vbsim::hw
