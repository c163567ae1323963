// vbsim replay: functional replay of a trace, streamed, or the cycle-level
// model's replay of it (--mode cycle).
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "progress/work_progress.h"
#include "hw/cycle_replay.h"
#include "hw/observe/host_memory_estimate.h"
#include "hw/observe/trace_scope.h"
#include "hw/sampling/sampled_replay.h"
#include "hw/sink/trace_order_buffer.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"

#include "commands.h"
#include "energy/operation_energy.h"
#include "exit_codes.h"
#include "method_options.h"
#include "output_provenance.h"
#include "progress/progress_meter.h"
#include "provenance/provenance.h"
#include "replay/replay_run.h"
#include "systemc_messages.h"
#include "tech_option.h"
#include "threads_option.h"
#include "trace/checked_trace_source.h"
#include "trace/trace_file.h"
#include "trace/trace_ray_count.h"

namespace vbsim::cli {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_interrupt(int) { g_stop.store(true); }

/// SIGINT and SIGTERM stop the run at the next ray (statistics marked
/// partial); the previous handlers come back when it ends or throws.
class InterruptScope {
 public:
  InterruptScope() {
    g_stop = false;
    int_ = std::signal(SIGINT, on_interrupt);
    term_ = std::signal(SIGTERM, on_interrupt);
  }
  ~InterruptScope() {
    std::signal(SIGINT, int_);
    std::signal(SIGTERM, term_);
  }

 private:
  void (*int_)(int);
  void (*term_)(int);
};

struct ReplayArgs {
  std::string trace;
  std::string stats;
  std::string hits;
  std::string mode = "functional";
  std::string preset;  // cycle mode: hardware preset (default: the config's, else small)
  std::string vcd, timeline, trace_scope, deps, missing_parents, ray_log, interval_stats;
  std::optional<uint64_t> interval, warmup_rays, warmup_cycles;  // cycle mode: override hw.sim's
  uint64_t timeline_start = 0, timeline_cycles = 2000, vcd_start = 0, vcd_cycles = 2000;
  bool timeline_window_given = false;  // --timeline-start or --timeline-cycles on the command line
  bool vcd_window_given = false;       // --vcd-start or --vcd-cycles on the command line
  bool quiet = false;
  std::string tech;  // --tech FILE (empty: the shipped default)
  MethodOptions method;
  int threads = 1;             // --threads (every core by default)
  bool threads_given = false;  // --threads on the command line
  // Sampled cycle-level simulation (docs/sampling.md).
  bool sample = false;
  hw::SamplingConfig sampling;
  std::string sample_error;        // --sample-error: "1%" or 0.01 (empty: no stopping rule)
  bool sample_options_given = false;
  bool sample_unit_given = false, sample_warmup_given = false;  // else they follow the source's window
  bool sample_no_warm = false;
};

/// --sample-error's value: a percentage ("1%") or a fraction ("0.01").
double parse_sample_error(const std::string& text) {
  std::string t = text;
  double scale = 1;
  if (!t.empty() && t.back() == '%') t.pop_back(), scale = 0.01;
  try {
    size_t used = 0;
    const double v = std::stod(t, &used);
    if (used != t.size() || !(v > 0)) throw std::invalid_argument("");
    return v * scale;
  } catch (const std::exception&) {
    throw UsageError(fmt::format("option '--sample-error': '{}' is not a positive fraction or percentage (e.g. 1%)",
                                 text));
  }
}

/// One line of the ray log.
std::string ray_log_line(const hw::RayTimes& t) {
  return fmt::format(
      R"({{"id":{},"parent":{},"enter":{},"ready":{},"emit":{},"start":{},"finish":{},"core":{},"slot":{}}})"
      "\n",
      t.id, t.parent, t.entered, t.ready, t.emitted, t.started, t.finished, t.core, t.slot);
}

ReplayStats run_cycle_mode(const ReplayArgs& a, const ReplayOptions& opt, const TechFile& tech, TraceSource& source,
                           const SceneAndBvh& sb, std::ostream* hits, ProgressMeter& meter, nlohmann::json& config,
                           nlohmann::json& hw, std::string& table) {
  hw::HwConfig cfg = hw::resolve_hw_config(a.method.config, a.preset);
  if (hw::slot_host_bytes(cfg) >= hw::kSlotMemoryWarningBytes)
    fmt::print(stderr, "vbsim: warning: hw: {} ray slots ({} cores x {} slots_per_core) take about {} MB of host memory\n",
               uint64_t{cfg.cores} * cfg.slots_per_core, cfg.cores, cfg.slots_per_core,
               hw::slot_host_bytes(cfg) >> 20);
  if (!a.deps.empty()) cfg.source.dependencies = a.deps == "on";
  if (a.interval) cfg.interval_cycles = *a.interval;
  if (a.warmup_rays) cfg.warmup_rays = *a.warmup_rays, cfg.warmup_cycles = 0;
  if (a.warmup_cycles) cfg.warmup_cycles = *a.warmup_cycles, cfg.warmup_rays = 0;
  if (!a.missing_parents.empty())
    cfg.source.missing_parents =
        a.missing_parents == "independent" ? hw::MissingParents::Independent : hw::MissingParents::Error;
  config["hw"] = hw::hw_config_json(hw::for_tester(cfg, opt.tester));
  source.set_triangle_count(sb.scene.size());
  hw::CycleRunOptions run;
  run.stop = &g_stop;
  run.tech = &tech;
  if (meter.shown()) run.progress = [&meter](const hw::CycleEngine& e) { meter.update(e.rays_done()); };
  run.vcd = {a.vcd, a.vcd_start, a.vcd_cycles, a.trace_scope};
  run.timeline = {a.timeline, a.timeline_start, a.timeline_cycles, a.trace_scope};
  run.interval_stats = a.interval_stats;
  // Rays finish out of order; the hits file lists them in trace order, as the functional replay does.
  std::unique_ptr<hw::TraceOrderBuffer> ordered;
  if (hits) ordered = std::make_unique<hw::TraceOrderBuffer>(*hits);
  const hw::RayResultSink sink = [&ordered, hits](const TraceRay& tr, const RayOutcome& out, uint64_t, uint64_t index) {
    ordered->put(index, hit_json_line(tr, out));
    check_hits_stream(*hits, "hits output");
  };
  run.locator = [&source](const std::string& field, const std::string& message) {
    return std::string(source.error_at_last_ray(field, message).what());
  };
  // The ray log: one JSON line per ray, in trace order.
  std::unique_ptr<AtomicOutputFile> log_file;
  std::unique_ptr<hw::TraceOrderBuffer> log;
  if (!a.ray_log.empty()) {
    log_file = std::make_unique<AtomicOutputFile>(a.ray_log);
    log = std::make_unique<hw::TraceOrderBuffer>(log_file->stream());
    run.ray_times = [&log](const hw::RayTimes& t) { log->put(t.trace_index, ray_log_line(t)); };
  }
  hw::CycleRunResult r = replay_at_trace_ray(source, [&] {
    const hw::RayFeed feed = [&source](TraceRay& tr) { return source.next(tr); };
    if (a.sample) {
      hw::SamplingConfig sampling = a.sampling;
      // Units and warm-ups shorter than the rays the source keeps in flight are
      // measured in a machine still filling or draining: biased on a
      // memory-bound run (docs/sampling.md). By default they follow the window.
      const uint64_t window = cfg.source.window;
      if (!a.sample_unit_given) sampling.unit = std::max<uint64_t>(sampling.unit, window);
      if (!a.sample_warmup_given) sampling.warmup = std::max<uint64_t>(sampling.warmup, 2 * window);
      if (!a.sample_error.empty()) sampling.error = parse_sample_error(a.sample_error);
      sampling.warm = !a.sample_no_warm;
      // The tail stratum needs the trace's length beforehand: read from a file, unknown from a pipe.
      std::error_code ec;
      if (std::filesystem::is_regular_file(a.trace, ec)) sampling.total = count_trace_rays(a.trace);
      try {
        hw::check_sampling_config(sampling);
      } catch (const std::invalid_argument& e) {
        const std::string what = e.what();  // "--sample-unit: must be >= 1"
        const size_t colon = what.find(':');
        throw UsageError(fmt::format("option '{}'{}", what.substr(0, colon), what.substr(colon)));
      }
      return hw::run_sampled_cycle_replay(feed, sb.scene, sb.bvh, opt, cfg, hits ? sink : hw::RayResultSink{}, run,
                                          sampling);
    }
    return hw::run_cycle_replay(feed, sb.scene, sb.bvh, opt, cfg, hits ? sink : hw::RayResultSink{}, run);
  });
  if (ordered) ordered->flush();  // a stopped run: the finished rays after the first dropped one
  if (log) {
    log->flush();
    log_file->commit();
  }
  if (const uint64_t n = r.hw["emission"].value("parents_not_found", uint64_t{0}); n != 0 && !a.quiet)
    fmt::print(stderr,
               "vbsim: warning: {} child ray{} replayed as independent rays: {} parent not found among the rays "
               "before {} (the first: {})\n",
               n, n == 1 ? "" : "s", n == 1 ? "its" : "their", n == 1 ? "it" : "them",
               r.hw["emission"]["first_parent_not_found"].get<std::string>());
  hw = std::move(r.hw);
  table = std::move(r.table);
  return r.stats;
}

void check_mode_options(const ReplayArgs& a) {
  if (a.mode != "functional" && a.mode != "cycle")
    throw UsageError(fmt::format("option '--mode': '{}' is not available; modes: functional, cycle", a.mode));
  if (a.mode != "cycle" && (!a.preset.empty() || !a.vcd.empty() || !a.timeline.empty() || a.timeline_window_given ||
                            a.vcd_window_given || !a.deps.empty() || !a.missing_parents.empty() || !a.ray_log.empty() ||
                            !a.trace_scope.empty() || !a.interval_stats.empty() || a.interval || a.warmup_rays ||
                            a.warmup_cycles))
    throw UsageError(
        "options '--preset', '--vcd', '--vcd-start', '--vcd-cycles', '--timeline', '--timeline-start', "
        "'--timeline-cycles', '--trace-scope', '--deps', '--missing-parents', '--ray-log', '--interval-stats', "
        "'--interval', '--warmup-rays' and '--warmup-cycles' need '--mode cycle'");
  if (a.sample_options_given && !a.sample)
    throw UsageError("options '--sample-unit', '--sample-interval', '--sample-warmup', '--sample-head', "
                     "'--sample-tail', '--sample-offset', "
                     "'--sample-confidence', '--sample-error', '--sample-min-units' and '--sample-no-warm' need "
                     "'--sample'");
  if (a.sample && a.mode != "cycle") throw UsageError("option '--sample' needs '--mode cycle'");
  if (a.sample && (!a.vcd.empty() || !a.timeline.empty() || !a.ray_log.empty() || !a.interval_stats.empty() ||
                   a.warmup_rays || a.warmup_cycles))
    throw UsageError("option '--sample' does not go with '--vcd', '--timeline', '--ray-log', '--interval-stats', "
                     "'--warmup-rays' or '--warmup-cycles'");
  if (a.mode == "cycle" && a.threads_given)
    throw UsageError("option '--threads' is for the functional replay; the cycle-level model runs on one thread");
  check_threads_option(a.threads);
  if (a.interval && a.interval_stats.empty()) throw UsageError("option '--interval' needs '--interval-stats FILE'");
  if (a.interval && *a.interval == 0) throw UsageError("option '--interval': must be > 0");
  if (a.warmup_rays && a.warmup_cycles)
    throw UsageError("options '--warmup-rays' and '--warmup-cycles': give at most one");
  if (a.timeline_window_given && a.timeline.empty())
    throw UsageError("options '--timeline-start' and '--timeline-cycles' need '--timeline FILE'");
  if (a.vcd_window_given && a.vcd.empty())
    throw UsageError("options '--vcd-start' and '--vcd-cycles' need '--vcd FILE'");
  if (a.timeline_cycles == 0) throw UsageError("option '--timeline-cycles': must be > 0");
  if (a.vcd_cycles == 0) throw UsageError("option '--vcd-cycles': must be > 0");
  check_preset_name(a.preset);
}

int run_replay_command(const ReplayArgs& a) {
  check_mode_options(a);
  set_systemc_quiet(a.quiet);
  const ReplayOptions opt = resolve_method_options(a.method);
  const TechFile tech = resolve_tech(a.tech);
  auto file = open_trace(a.trace);
  // Before any long work: no output may overwrite an input or another output,
  // and every output must be creatable.
  check_output_paths({{"trace", a.trace},
                      {"option '--config'", a.method.config},
                      {"option '--tech'", a.tech},
                      {"scene", file->header().scene_path}},
                     {{"option '--stats'", a.stats},
                      {"option '--hits'", a.hits},
                      {"option '--timeline'", a.timeline},
                      {"option '--vcd'", a.vcd},
                      {"option '--ray-log'", a.ray_log},
                      {"option '--interval-stats'", a.interval_stats}});
  std::unique_ptr<AtomicOutputFile> stats_file, hits_file;
  if (!a.stats.empty()) stats_file = std::make_unique<AtomicOutputFile>(a.stats);
  if (!a.hits.empty()) hits_file = std::make_unique<AtomicOutputFile>(a.hits);
  for (const std::string* later : {&a.timeline, &a.vcd})  // written at the end: creatable now
    if (!later->empty()) AtomicOutputFile(*later).discard();
  MeterWorkProgress loading("scene", ProgressMeter::terminal_or_null(a.quiet));
  const SceneAndBvh sb = load_trace_scene(file->header(), opt.bvh, &loading);
  loading.finish();
  // Every ray passes the consistency checks: a child before its parent is an
  // error, the other checks are counted warnings (docs/trace-format.md).
  TraceConsistencyChecker::Options checks;
  checks.triangles = &sb.scene.triangles;
  checks.window = static_cast<std::size_t>(opt.parent_window);  // one window for the checks and the replay
  auto source = std::make_unique<CheckedTraceSource>(*file, checks);
  // The inputs every output names with their checksums.
  const std::vector<std::string> inputs = {a.trace, file->header().scene_path, a.method.config, tech.path};

  if (hits_file) hits_file->stream() << hits_header_line(provenance_json(inputs));
  nlohmann::json config = replay_config_json(opt);
  nlohmann::json hw;  // cycle mode: the hw section
  std::string table;
  std::FILE* terminal = ProgressMeter::terminal_or_null(a.quiet);
  ProgressMeter meter(fmt::format("replay ({})", a.mode), terminal ? count_trace_rays(a.trace) : 0, "rays", terminal);
  std::ostream* hits = hits_file ? &hits_file->stream() : nullptr;
  ReplayStats stats;
  try {
    const InterruptScope interrupts;
    stats = a.mode == "cycle"
                ? run_cycle_mode(a, opt, tech, *source, sb, hits, meter, config, hw, table)
                : run_replay(*source, sb, opt, hits, &g_stop,
                             meter.shown() ? ReplayProgress([&meter](uint64_t n) { meter.update(n); }) : nullptr,
                             a.threads);
  } catch (const OutputError& e) {
    if (e.path == "hits output") throw OutputError(a.hits, e.message);
    throw;
  } catch (const hw::TraceScopeError& e) {
    throw UsageError(fmt::format("option '--trace-scope': {}", e.what()));
  }
  meter.finish();
  if (hits_file) {  // a stopped run's hits end with a line that says so
    if (stats.partial) hits_file->stream() << partial_hits_marker(stats.total().rays);
    hits_file->commit();
  }

  // The checksums (read once, cached) only when a file will record them.
  const bool records = !a.stats.empty() || !a.vcd.empty() || !a.timeline.empty();
  const nlohmann::json provenance = records ? provenance_json(inputs) : nlohmann::json();
  if (!a.vcd.empty()) add_vcd_provenance(a.vcd, provenance);
  if (!a.timeline.empty()) add_timeline_provenance(a.timeline, provenance);
  if (stats_file) {
    config["trace"] = a.trace;
    config["scene"] = source->header().scene_path;
    config["triangles"] = sb.scene.size();
    nlohmann::json j = stats.to_json(config);
    // The operations' energy in both modes; the cycle-level model adds memory and leakage in hw.energy.
    j["energy"] = operation_energy_json(tech, operation_energy(tech, opt.method, opt.tester, stats),
                                        stats.total().rays);
    if (!hw.is_null()) j["hw"] = std::move(hw);
    j["provenance"] = provenance;
    j["checks"] = source->summary_json();
    stats_file->stream() << j.dump(2) << "\n";
    stats_file->commit();
  }
  if (!a.quiet) {
    fmt::print(stderr, "{}", source->warning_lines("vbsim replay", false));
    fmt::print("vbsim replay {}  method {}  tester {}  scene {} ({} triangles)\n", a.trace,
               opt.method.name(), tester_name(opt.tester), source->header().scene, sb.scene.size());
    fmt::print("{}{}", stats.summary(), table);
    if (a.mode != "cycle") {
      const OperationEnergy e = operation_energy(tech, opt.method, opt.tester, stats);
      const uint64_t rays = stats.total().rays;
      fmt::print("energy (operations only, no memory): {:.4g} pJ/ray, the method {:.4g} pJ/ray ({})\n",
                 per_ray(e.total(), rays), per_ray(e.method, rays), tech.path);
    }
  }
  return stats.partial ? kExitInterrupted : kExitSuccess;
}

}  // namespace

std::string default_trace_path() { return std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl"; }

void add_replay_command(CLI::App& app) {
  auto args = std::make_shared<ReplayArgs>();
  CLI::App* cmd = app.add_subcommand("replay", "replay a trace untimed and score every method's answer");
  cmd->add_option("trace", args->trace, "trace file (.jsonl text or .vbt binary)")->required();
  cmd->add_option("--mode", args->mode, "replay mode: functional (untimed) or cycle (the SystemC hardware model)")
      ->capture_default_str();
  cmd->add_option("--preset", args->preset, "cycle mode: hardware preset, small, large or rtcore [the config's hw.preset, else small]");
  cmd->add_option("--vcd", args->vcd,
                  "cycle mode: write a VCD of per-instance values (busy slots, operations in flight, L1 misses) here");
  CLI::Option* vcd_start =
      cmd->add_option("--vcd-start", args->vcd_start, "cycle mode: first cycle of the VCD window")->capture_default_str();
  CLI::Option* vcd_cycles =
      cmd->add_option("--vcd-cycles", args->vcd_cycles, "cycle mode: cycles in the VCD window")->capture_default_str();
  cmd->add_option("--trace-scope", args->trace_scope,
                  "cycle mode: record only these instances and what is below them in the VCD and the timeline: "
                  "hierarchical names, comma-separated, '*' for any characters within one level (e.g. "
                  "accelerator.core_3 or accelerator.core_*,accelerator.l2); one that names no instance is an error");
  cmd->add_option("--timeline", args->timeline, "cycle mode: write a Chrome trace-event JSON of a cycle window here");
  CLI::Option* start = cmd->add_option("--timeline-start", args->timeline_start,
                                       "cycle mode: first cycle of the timeline window")->capture_default_str();
  CLI::Option* cycles = cmd->add_option("--timeline-cycles", args->timeline_cycles,
                                        "cycle mode: cycles in the timeline window")->capture_default_str();
  cmd->add_option("--deps", args->deps,
                  "cycle mode: on (a child ray waits for its parent's result plus the shading latency) or off (every "
                  "ray independent, as a trace of unrelated queries) [the config's hw.source.dependencies, else on]")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--missing-parents", args->missing_parents,
                  "cycle mode, dependencies on: a child whose parent is not among the --parent-window rays before it "
                  "is an error naming its line (error), or replayed as an independent ray, counted and warned about "
                  "(independent) [the config's hw.source.missing_parents, else error]")
      ->check(CLI::IsMember({"error", "independent"}));
  cmd->add_option("--ray-log", args->ray_log,
                  "cycle mode: write one JSON line per ray here, in trace order: id, parent, enter (the source's "
                  "buffer), ready, emit, start and finish cycles, core, slot");
  cmd->add_option("--interval-stats", args->interval_stats,
                  "cycle mode: write interval statistics here, one JSON line per interval of --interval cycles: rays "
                  "finished, rays/cycle, cache hits and misses per level, DRAM bytes, unit busy fractions");
  cmd->add_option("--interval", args->interval,
                  "cycle mode: cycles per interval of --interval-stats [the config's hw.sim.interval_cycles, else 1000]");
  cmd->add_option("--warmup-rays", args->warmup_rays,
                  "cycle mode: hw.measured counts from the cycle after the N-th ray finished on "
                  "[the config's hw.sim.warmup_rays, else none]");
  cmd->add_option("--warmup-cycles", args->warmup_cycles,
                  "cycle mode: hw.measured counts from cycle C on [the config's hw.sim.warmup_cycles, else none]");
  CLI::Option* sample = cmd->add_flag(
      "--sample", args->sample,
      "cycle mode: sampled simulation (docs/sampling.md): measure one unit of rays in every --sample-interval, "
      "fast-forward the rest functionally while warming the caches; hits and verdicts stay exact, cycles, rays/cycle "
      "and hit rates are estimates with confidence intervals (hw.sampling)");
  std::vector<CLI::Option*> sample_options = {
      cmd->add_option("--sample-unit", args->sampling.unit,
                      "with --sample: rays per measurement unit [1000, or the source's window if larger]"),
      cmd->add_option("--sample-interval", args->sampling.interval,
                      "with --sample: one unit measured every K units (1: every unit)")
          ->capture_default_str(),
      cmd->add_option("--sample-warmup", args->sampling.warmup,
                      "with --sample: rays simulated in detail, unmeasured, before each measured unit [1000, or "
                      "twice the source's window if larger]"),
      cmd->add_option("--sample-head", args->sampling.head,
                      "with --sample: the trace's first rays, simulated in detail and measured whole")
          ->capture_default_str(),
      cmd->add_option("--sample-tail", args->sampling.tail,
                      "with --sample: its last rays, the same (a trace read from a pipe has none)")
          ->capture_default_str(),
      cmd->add_option("--sample-offset", args->sampling.offset,
                      "with --sample: which unit of each interval is measured, 0 .. K-1 [K/2]"),
      cmd->add_option("--sample-confidence", args->sampling.confidence,
                      "with --sample: confidence of the intervals")
          ->capture_default_str(),
      cmd->add_option("--sample-error", args->sample_error,
                      "with --sample: stop measuring once the cycles' interval half-width is within this of the "
                      "estimate (e.g. 1%), else measure to the trace's end [none]"),
      cmd->add_option("--sample-min-units", args->sampling.min_units,
                      "with --sample-error: units measured before the stopping rule may act")
          ->capture_default_str(),
      cmd->add_flag("--sample-no-warm", args->sample_no_warm,
                    "with --sample: fast-forwarded rays leave the caches alone (to see what warming is worth)")};
  cmd->add_option("--stats", args->stats, "write the statistics JSON here");
  cmd->add_option("--hits", args->hits, "write one JSON line per ray here (after a provenance line)");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success (no progress, no SystemC info messages)");
  add_tech_option(*cmd, args->tech);
  CLI::Option* threads =
      add_threads_option(*cmd, args->threads, "functional mode: threads that parse and replay the rays");
  add_method_options(*cmd, args->method, "none");
  cmd->callback([args, start, cycles, vcd_start, vcd_cycles, threads, sample, sample_options] {
    (void)sample;
    args->sample_options_given = false;
    for (const CLI::Option* o : sample_options) args->sample_options_given |= o->count() > 0;
    args->sample_unit_given = sample_options[0]->count() > 0;
    args->sample_warmup_given = sample_options[2]->count() > 0;
    args->threads_given = threads->count() > 0;
    args->timeline_window_given = start->count() > 0 || cycles->count() > 0;
    args->vcd_window_given = vcd_start->count() > 0 || vcd_cycles->count() > 0;
    const int rc = run_replay_command(*args);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

int run_default_job() {
  ReplayArgs a;
  a.threads = all_cores();
  a.trace = default_trace_path();
  a.method.default_method = "validity-bit";
  const int rc = run_replay_command(a);
  print_tradeoff_table(a.trace);
  return rc;
}

}  // namespace vbsim::cli
