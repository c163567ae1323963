// Sampled cycle-level simulation (hw/sampling/, docs/sampling.md): the
// estimator's arithmetic by hand; with every unit measured the sampled run is
// the full run; a sampled run's answers are the full run's, ray by ray; the
// full run's cycles lie inside the interval on two generated path traces
// (92,488 rays over the bunny, 81,968 over Wuson), both presets; and warming the caches while
// fast-forwarding brings the first measured unit's L2 hit rate and cycles to
// the full run's, where without it the unit starts cold.
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

/// `vbsim gen paths --rays 40000 --seed 3 --set scene=traces/wuson/WusonOBJ.obj`: 81,968 rays.
const TraceInMemory& wuson() {
  static const TraceInMemory t = [] {
    const auto dir = vbsim::test::scratch_dir("sampling_wuson");
    REQUIRE(vbsim::test::run_vbsim("gen paths --rays 40000 --seed 3 --set scene=" + std::string(VBSIM_SOURCE_DIR) +
                                   "/traces/wuson/WusonOBJ.obj -q -o " + dir.string())
                .exit_code == 0);
    TraceInMemory r = read_trace((dir / "paths.jsonl").string());
    std::filesystem::remove_all(dir);
    return r;
  }();
  return t;
}

double l2_hit_rate(const nlohmann::json& unit) {
  return unit["l2_hits"].get<double>() / unit["l2_accesses"].get<double>();
}

}  // namespace

TEST_CASE("sampling: the plan and the estimator by hand", "[module][sampling]") {
  SamplingConfig c;
  c.unit = 10, c.interval = 4, c.warmup = 3, c.offset = 1, c.head = 0, c.tail = 0;
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
  // A head of 15 and a tail of 12 of 100 rays: body units from 15 (15..24, 25..34, ...); unit 1
  // (25..34) and unit 5 (65..74) measured; the last unit cut short at the tail (88).
  c.head = 15, c.tail = 12, c.total = 100;
  const SamplePlan q(c);
  CHECK(q.detailed(0));
  CHECK(q.detailed(14));
  CHECK(!q.detailed(15));
  CHECK(q.detailed(22));  // warm-up of 25..34
  CHECK(q.starts_measured_unit(25));
  CHECK(!q.starts_measured_unit(30));
  CHECK(!q.detailed(35));
  CHECK(q.starts_measured_unit(65));
  CHECK(!q.detailed(84));
  CHECK(q.detailed(85));  // warm-up of the tail
  CHECK(q.detailed(99));
  CHECK(q.tail_start() == 88);
  CHECK(q.unit_rays(q.body_unit(85)) == 3);

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
  CHECK(e.half_width == Approx(3.1824 * std::sqrt(800.0 / 3 / 4) / 10).epsilon(2e-3));
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
    s.unit = 100, s.interval = 1, s.warmup = 0, s.head = 0, s.tail = 0;
    const Run sampled = run(t, cfg, &s);
    const nlohmann::json& hs = sampled.r.hw["sampling"];
    CHECK(hs["rays_fast_forwarded"] == 0);
    CHECK(hs["units_measured"] == 11);
    // With a head and a tail measured whole, the body's units between them tile it too.
    SamplingConfig st = s;
    st.head = 130, st.tail = 150, st.total = t.rays.size();
    const Run strata = run(t, cfg, &st);
    CHECK(strata.r.hw["cycles"] == full.r.counters.cycles);
    CHECK(strata.r.hw["sampling"]["strata"]["head"]["rays"] == 130);
    CHECK(strata.r.hw["sampling"]["strata"]["tail"]["rays"] == 150);
    CHECK(strata.r.hw["sampling"]["units_measured"] == 8);  // 130..229, ..., 730..829, 830..857
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
  s.unit = 50, s.interval = 5, s.warmup = 60, s.head = 50, s.tail = 50, s.total = t.rays.size();
  const Run sampled = run(t, cfg, &s);
  CHECK(sampled.r.hw["sampling"]["rays_fast_forwarded"].get<uint64_t>() > 400);
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
    uint64_t unit, interval, warmup, head, tail;
  };
  // Not the bundled trace: its 1,008 rays fit in the ray source's window, so
  // the whole trace is in flight at once, finishing in the order of its
  // dependencies, and a unit of it is no sample of a steady stream.
  for (const Case& c : {Case{&generated(), 1000, 10, 1000, 10000, 2000}, Case{&wuson(), 1000, 10, 1000, 10000, 2000}})
    for (const char* preset : {"small", "large"}) {
      INFO(preset << ", " << c.t->rays.size() << " rays");
      const HwConfig cfg = load_preset(preset, "test");
      const Run full = run(*c.t, cfg, nullptr);
      SamplingConfig s;
      s.unit = c.unit, s.interval = c.interval, s.warmup = c.warmup;
      s.head = c.head, s.tail = c.tail, s.total = c.t->rays.size();
      const Run sampled = run(*c.t, cfg, &s);
      const nlohmann::json& iv = sampled.r.hw["sampling"]["intervals"]["cycles"];
      const double cycles = static_cast<double>(full.r.counters.cycles);
      INFO("full " << cycles << ", estimate " << sampled.r.hw["cycles"] << ", interval " << iv);
      CHECK(iv[0].get<double>() <= cycles);
      CHECK(cycles <= iv[1].get<double>());
      CHECK(sampled.r.hw["sampling"]["rays_fast_forwarded"].get<double>() > 0.3 * c.t->rays.size());
      CHECK(sampled.answers == full.answers);
    }
}

TEST_CASE("sampling: warming the caches while fast-forwarding gives the first unit the full run's L2 hit rate",
          "[module][sampling]") {
  // No detailed warm-up (W = 0): the first measured unit, unit 5, starts from
  // what fast-forwarding left. The L2 (1 MiB) holds most of this scene's BVH
  // once warm; cold, a unit misses it for a large part of its rays.
  const TraceInMemory& t = generated();
  const HwConfig cfg = load_preset("small", "test");
  SamplingConfig all;
  all.unit = 1000, all.interval = 1, all.warmup = 0, all.head = 0, all.tail = 0;
  const Run full = run(t, cfg, &all);  // every unit measured: the full run's figures per unit
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
  const double full_rate = l2_hit_rate(u_full), warm_rate = l2_hit_rate(u_warm), cold_rate = l2_hit_rate(u_cold);
  INFO("L2 hit rate of unit 5: full run " << full_rate << ", warmed " << warm_rate << ", cold " << cold_rate);
  CHECK(std::fabs(warm_rate - full_rate) < 0.02);
  CHECK(full_rate - cold_rate > 0.1);
  // And the unit's cycles: within 15% of the full run's warmed, more than twice them cold.
  const double full_cycles = u_full["cycles"].get<double>();
  INFO("cycles of unit 5: full run " << full_cycles << ", warmed " << u_warm["cycles"] << ", cold " << u_cold["cycles"]);
  CHECK(std::fabs(u_warm["cycles"].get<double>() - full_cycles) < 0.15 * full_cycles);
  CHECK(u_cold["cycles"].get<double>() > 2 * full_cycles);
}
