// Sampled cycle-level simulation (hw/sampling/, docs/sampling.md): the
// estimator's arithmetic by hand; with every unit measured the sampled run is
// the full run; a sampled run's answers are the full run's, ray by ray; the
// full run's cycles lie inside the interval on the bundled trace and on a
// generated 93,000-ray path trace; and warming the caches while
// fast-forwarding brings the first measured unit's L1 hit rate to the full
// run's, where without it the unit starts cold.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <vector>

#include "accelerator_harness.h"
#include "hw/cycle_replay.h"
#include "hw/sampling/sample_estimator.h"
#include "hw/sampling/sample_plan.h"
#include "hw/sampling/sampled_replay.h"
#include "trace_in_memory.h"
#include "../system/run_vbsim.h"
#include "../unit/three_floors.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

struct Answer {
  int32_t prim;
  float t;
  int verdict;
  bool operator==(const Answer& o) const { return prim == o.prim && t == o.t && verdict == o.verdict; }
};

struct Run {
  CycleRunResult r;
  std::map<uint64_t, Answer> answers;  ///< by trace position
};

Run run(const TraceInMemory& t, const HwConfig& cfg, const SamplingConfig* sampling) {
  Run out;
  const RayResultSink sink = [&out](const TraceRay&, const RayOutcome& o, uint64_t, uint64_t index) {
    const bool fresh = out.answers.emplace(index, Answer{o.hit.prim, o.hit.t, static_cast<int>(o.verdict)}).second;
    REQUIRE(fresh);  // every trace position once
  };
  out.r = sampling ? run_sampled_cycle_replay(feed_of(t.rays), t.sb.scene, t.sb.bvh, ReplayOptions{}, cfg, sink, {},
                                              *sampling)
                   : run_cycle_replay(feed_of(t.rays), t.sb.scene, t.sb.bvh, ReplayOptions{}, cfg, sink, {});
  return out;
}

const TraceInMemory& bundled() {
  static const TraceInMemory t = read_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  return t;
}

/// `vbsim gen paths --rays 20000 --seed 5`: 92,488 rays.
const TraceInMemory& generated() {
  static const TraceInMemory t = [] {
    const auto dir = vbsim::test::scratch_dir("sampling_paths");
    REQUIRE(vbsim::test::run_vbsim("gen paths --rays 20000 --seed 5 -q -o " + dir.string()).exit_code == 0);
    TraceInMemory r = read_trace((dir / "paths.jsonl").string());
    std::filesystem::remove_all(dir);
    return r;
  }();
  return t;
}

double hit_rate(const nlohmann::json& unit) {
  return unit["l1_hits"].get<double>() / unit["l1_accesses"].get<double>();
}

}  // namespace

TEST_CASE("sampling: the plan and the estimator by hand", "[module][sampling]") {
  SamplingConfig c;
  c.unit = 10, c.interval = 4, c.warmup = 3, c.offset = 1;
  const SamplePlan p(c);
  // Units 1, 5, 9, ... are measured: positions 10..19, 50..59; warm-up 7..9, 47..49.
  CHECK(!p.detailed(0));
  CHECK(!p.detailed(6));
  CHECK(p.detailed(7));
  CHECK(p.detailed(19));
  CHECK(!p.detailed(20));
  CHECK(!p.detailed(46));
  CHECK(p.detailed(47));
  CHECK(p.next_measured_start(25) == 50);
  CHECK(p.next_measured_start(10) == 10);

  CHECK(normal_quantile(0.975) == Approx(1.959964).epsilon(1e-6));
  CHECK(student_t_quantile(0.975, 1) == Approx(12.7062).epsilon(1e-4));
  CHECK(student_t_quantile(0.975, 2) == Approx(4.3027).epsilon(1e-4));
  CHECK(student_t_quantile(0.975, 4) == Approx(2.7764).epsilon(1e-3));
  CHECK(student_t_quantile(0.975, 10) == Approx(2.2281).epsilon(1e-3));
  CHECK(student_t_quantile(0.995, 30) == Approx(2.7500).epsilon(1e-3));

  // Units of 10 rays taking 100, 120, 80, 100 cycles: R = 10, residuals 0, 20,
  // -20, 0: s^2 = 800 / 3, SE(R) = sqrt(800 / 3 / 4) / 10 = 0.8165; t(0.975, 3) = 3.1824.
  const std::vector<UnitMeasure> u = {{100, 10}, {120, 10}, {80, 10}, {100, 10}};
  const RatioEstimate e = ratio_estimate(u, 0.95, 0);
  CHECK(e.ratio == Approx(10));
  CHECK(e.half_width == Approx(3.1824 * std::sqrt(800.0 / 3 / 4) / 10).epsilon(1e-3));
  CHECK(ratio_estimate(u, 0.95, 40).half_width == 0);  // the whole population measured
  CHECK(ratio_estimate(u, 0.95, 80).half_width == Approx(e.half_width * std::sqrt(0.5)).epsilon(1e-9));
  CHECK(std::isinf(ratio_estimate({{100, 10}}, 0.95, 0).half_width));
}

TEST_CASE("sampling: with every unit measured and nothing fast-forwarded the sampled run is the full run",
          "[module][sampling]") {
  const TraceInMemory& t = bundled();
  for (const char* preset : {"small", "large"}) {
    INFO(preset);
    const HwConfig cfg = load_preset(preset, "test");
    const Run full = run(t, cfg, nullptr);
    SamplingConfig s;
    s.unit = 100, s.interval = 1, s.warmup = 0;
    const Run sampled = run(t, cfg, &s);
    const nlohmann::json& hs = sampled.r.hw["sampling"];
    CHECK(hs["rays_fast_forwarded"] == 0);
    CHECK(hs["units_measured"] == 11);
    CHECK(sampled.r.hw["sampling"]["detailed"]["cycles"] == full.r.counters.cycles);
    CHECK(sampled.r.hw["cycles"] == full.r.counters.cycles);
    CHECK(hs["intervals"]["cycles"][0].get<double>() == Approx(full.r.counters.cycles));
    CHECK(hs["intervals"]["cycles"][1].get<double>() == Approx(full.r.counters.cycles));
    CHECK(sampled.answers == full.answers);
    nlohmann::json a = sampled.r.stats.to_json({}), b = full.r.stats.to_json({});
    a.erase("sim"), b.erase("sim");
    CHECK(a == b);
    // The L1 hit rate over the units is the run's.
    CHECK(hs["estimates"]["l1_hit_rate"].get<double>() ==
          Approx(full.r.hw["memory"]["port"]["l1"]["hit_rate"].get<double>()));
  }
}

TEST_CASE("sampling: a sampled run answers every ray as the full run does", "[module][sampling]") {
  const TraceInMemory& t = bundled();
  const HwConfig cfg = load_preset("small", "test");
  const Run full = run(t, cfg, nullptr);
  SamplingConfig s;
  s.unit = 50, s.interval = 5, s.warmup = 60;
  const Run sampled = run(t, cfg, &s);
  CHECK(sampled.r.hw["sampling"]["rays_fast_forwarded"].get<uint64_t>() > 500);
  REQUIRE(sampled.answers.size() == t.rays.size());
  CHECK(sampled.answers == full.answers);
  nlohmann::json a = sampled.r.stats.to_json({}), b = full.r.stats.to_json({});
  a.erase("sim"), b.erase("sim");
  CHECK(a == b);  // verdicts, per-kind figures, traversal work: every ray's
  CHECK(sampled.r.hw["rays"] == t.rays.size());
}

TEST_CASE("sampling: the full run's cycles lie inside the interval", "[module][sampling]") {
  struct Case {
    const TraceInMemory* t;
    uint64_t unit, interval, warmup;
  };
  for (const Case& c : {Case{&bundled(), 50, 4, 100}, Case{&generated(), 1000, 10, 1000}})
    for (const char* preset : {"small", "large"}) {
      INFO(preset << ", " << c.t->rays.size() << " rays");
      const HwConfig cfg = load_preset(preset, "test");
      const Run full = run(*c.t, cfg, nullptr);
      SamplingConfig s;
      s.unit = c.unit, s.interval = c.interval, s.warmup = c.warmup;
      const Run sampled = run(*c.t, cfg, &s);
      const nlohmann::json& iv = sampled.r.hw["sampling"]["intervals"]["cycles"];
      const double cycles = static_cast<double>(full.r.counters.cycles);
      INFO("full " << cycles << ", estimate " << sampled.r.hw["cycles"] << ", interval " << iv);
      CHECK(iv[0].get<double>() <= cycles);
      CHECK(cycles <= iv[1].get<double>());
      CHECK(sampled.r.hw["sampling"]["rays_fast_forwarded"].get<double>() > 0.5 * c.t->rays.size());
      CHECK(sampled.answers == full.answers);
    }
}

TEST_CASE("sampling: warming the caches while fast-forwarding gives the first unit the full run's L1 hit rate",
          "[module][sampling]") {
  const TraceInMemory& t = generated();
  const HwConfig cfg = load_preset("small", "test");
  SamplingConfig all;
  all.unit = 1000, all.interval = 1, all.warmup = 0;
  const Run full = run(t, cfg, &all);  // every unit measured: the full run's hit rate per unit
  SamplingConfig s = all;
  s.interval = 10, s.offset = 5;  // the first measured unit is unit 5, after 5,000 fast-forwarded rays
  const Run warm = run(t, cfg, &s);
  s.warm = false;
  const Run cold = run(t, cfg, &s);
  const nlohmann::json& u_full = full.r.hw["sampling"]["units"][5];
  const nlohmann::json& u_warm = warm.r.hw["sampling"]["units"][0];
  const nlohmann::json& u_cold = cold.r.hw["sampling"]["units"][0];
  REQUIRE(u_full["trace_start"] == 5000);
  REQUIRE(u_warm["trace_start"] == 5000);
  REQUIRE(u_cold["trace_start"] == 5000);
  const double full_rate = hit_rate(u_full), warm_rate = hit_rate(u_warm), cold_rate = hit_rate(u_cold);
  INFO("L1 hit rate of unit 5: full run " << full_rate << ", warmed " << warm_rate << ", cold " << cold_rate);
  CHECK(std::fabs(warm_rate - full_rate) < 0.02);
  CHECK(full_rate - cold_rate > 0.05);
  // And the unit's cycles: cold caches cost more.
  CHECK(u_cold["cycles"].get<double>() > u_warm["cycles"].get<double>());
}
