#include "hw/cycle_replay.h"

#include <chrono>
#include <memory>
#include <optional>

#include "hw/accelerator.h"
#include "hw/observe/hw_energy.h"
#include "hw/observe/timeline_recorder.h"
#include "hw/observe/vcd_recorder.h"
#include "hw/sampling/sampled_feed.h"
#include "hw/simulation_context.h"
#include "replay/ray_conservation.h"

namespace vbsim::hw {

namespace {

/// The hierarchical names of `root` and every module below it (not their
/// ports, exports, sockets or processes), parents first.
std::vector<std::string> instance_names(const sc_core::sc_object& root) {
  std::vector<const sc_core::sc_object*> modules{&root};
  for (size_t i = 0; i < modules.size(); ++i)
    for (const sc_core::sc_object* child : modules[i]->get_child_objects())
      if (dynamic_cast<const sc_core::sc_module*>(child)) modules.push_back(child);
  std::vector<std::string> out;
  for (const sc_core::sc_object* m : modules) out.push_back(m->name());
  return out;
}

/// A closed-loop shader whose rays are counted, for the conservation check.
class CountingShader final : public RayShader {
 public:
  CountingShader(RayShader& shader, uint64_t& cast) : shader_(shader), cast_(cast) {}
  ShaderAnswer next_ray(TraceRay& out, uint64_t cycle) override {
    const ShaderAnswer a = shader_.next_ray(out, cycle);
    cast_ += a == ShaderAnswer::Ray;
    return a;
  }
  void on_result(const TraceRay& ray, const RayOutcome& outcome, uint64_t cycle) override {
    shader_.on_result(ray, outcome, cycle);
  }

 private:
  RayShader& shader_;
  uint64_t& cast_;
};

/// What a run takes its rays from: a trace's feed or a closed-loop shader (one of the two).
struct RunInput {
  const RayFeed* feed = nullptr;
  RayShader* shader = nullptr;
};

CycleRunResult run_accelerator(const RunInput& input, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                               const HwConfig& cfg, const RayResultSink& sink, const CycleRunOptions& options) {
  const SimulationContext context;
  const auto start = std::chrono::steady_clock::now();
  auto acc = std::make_unique<Accelerator>("accelerator", cfg, scene, bvh, opt, options.units);
  std::optional<VcdRecorder> vcd;
  std::optional<TimelineRecorder> timeline;
  // A scope must name an instance of the design (TraceScopeError otherwise).
  const std::vector<std::string> instances = instance_names(*acc);
  if (!options.vcd.path.empty()) {
    const TraceScope scope(options.vcd.scope);
    scope.check(instances);
    vcd.emplace(options.vcd.first, options.vcd.cycles,
                static_cast<uint64_t>(CycleClock(cfg.clock_mhz).period().value()), scope);
  }
  if (!options.timeline.path.empty()) {
    const TraceScope scope(options.timeline.scope);
    scope.check(instances);
    timeline.emplace(options.timeline.path, options.timeline.first, options.timeline.cycles, scope);
  }
  acc->set_tracing(vcd ? &*vcd : nullptr, timeline ? &*timeline : nullptr);
  // Warm-up and interval statistics (hw.sim.warmup_*, options.interval_stats).
  StatisticsOptions statistics_options;
  statistics_options.interval_path = options.interval_stats;
  statistics_options.interval_cycles = cfg.interval_cycles;
  statistics_options.warmup_rays = cfg.warmup_rays;
  statistics_options.warmup_cycles = cfg.warmup_cycles;
  std::optional<RunStatistics> statistics;
  if (statistics_options.warmup() || !statistics_options.interval_path.empty()) {
    statistics.emplace(acc->config(), statistics_options);
    acc->set_statistics(&*statistics);
  }
  uint64_t fed = 0;  // rays in, for the conservation check
  std::optional<CountingShader> counted;
  if (input.shader) {
    acc->set_shader(counted.emplace(*input.shader, fed));
  } else if (options.sampled) {
    SampledFeed& sampled = *options.sampled;
    if (!acc->set_parents_fast_forwarded(true))
      throw std::invalid_argument("sampling: a replaced ray source cannot take fast-forwarded parents");
    sampled.attach(*acc);
    acc->set_feed([&sampled, &fed](TraceRay& tr) {
      const bool got = sampled.next_detailed(tr);
      fed += got ? 1 : 0;
      return got;
    });
  } else {
    acc->set_feed([&feed = *input.feed, &fed](TraceRay& tr) {
      const bool got = feed(tr);
      fed += got ? 1 : 0;
      return got;
    });
  }
  acc->set_locator(options.locator);
  acc->set_ray_times(options.ray_times);
  if (options.sampled)
    acc->set_result_callback([&sampled = *options.sampled](const TraceRay& tr, const RayOutcome& out, uint64_t cycle,
                                                           uint64_t index) { sampled.detailed_done(tr, out, cycle, index); });
  else
    acc->set_result_callback(sink);
  acc->set_track_parents(options.track_parents);
  acc->set_stop_flag(options.stop);
  acc->set_progress(options.progress);
  sc_core::sc_start();
  acc->check();

  CycleRunResult r;
  r.stats = acc->replayer().stats();
  r.stats.mode = "cycle";
  r.stats.partial = acc->partial();
  r.stats.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.sampled) fed += options.sampled->fast_forwarded();  // answered on the way, counted as done
  // Rays in = rays out; a stopped run drops the rays it had read and not finished.
  const uint64_t done = r.stats.total().rays;
  if (!r.stats.partial) check_ray_conservation("cycle-level replay", fed, done);
  else if (done > fed) check_ray_conservation("stopped cycle-level replay", fed, done);
  r.stats.rays_dropped = r.stats.partial ? fed - done : 0;
  r.counters = acc->chip_counters();
  if (statistics && !r.stats.partial) statistics->finish(acc->statistics_sample(r.counters.cycles + 1, true));
  // hw_json() prices the run's energy and area (nothing per cycle).
  if (options.tech) acc->set_technology(*options.tech);
  r.hw = acc->hw_json();
  r.table = acc->hw_table();
  r.table += hw_energy_lines(r.hw["energy"], r.hw["area"]);
  r.table += sram_range_lines(acc->technology(), acc->config());
  if (vcd) vcd->write(options.vcd.path, r.counters.cycles);
  if (timeline) timeline->finish();
  return r;
}

}  // namespace

CycleRunResult run_cycle_replay(const RayFeed& feed, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                                const HwConfig& cfg, const RayResultSink& sink, const CycleRunOptions& options) {
  return run_accelerator(RunInput{&feed, nullptr}, scene, bvh, opt, cfg, sink, options);
}

CycleRunResult run_cycle_closed_loop(RayShader& shader, const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                                     const HwConfig& cfg, const RayResultSink& sink, const CycleRunOptions& options) {
  return run_accelerator(RunInput{nullptr, &shader}, scene, bvh, opt, cfg, sink, options);
}

}  // namespace vbsim::hw
