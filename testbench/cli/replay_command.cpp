// vbsim replay: functional replay of a trace, streamed.
#include <fmt/format.h>

#include <atomic>
#include <csignal>
#include <fstream>
#include <iostream>
#include <memory>
#include <unistd.h>

#include "hw/cycle_replay.h"
#include "hw/trace_order_buffer.h"

#include "commands.h"
#include "method_options.h"
#include "replay/replay_run.h"
#include "trace/trace_file.h"

namespace vbsim::cli {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_interrupt(int) { g_stop.store(true); }

struct ReplayArgs {
  std::string trace;
  std::string stats;
  std::string hits;
  std::string mode = "functional";
  std::string preset;  // cycle mode: hardware preset (default: the config's, else small)
  std::string vcd, timeline;
  uint64_t timeline_start = 0, timeline_cycles = 2000;
  bool quiet = false;
  MethodOptions method;
};

/// A one-line progress report on stderr, rewritten in place.
void print_progress(const hw::CycleEngine& e) {
  const hw::HwCounters& c = e.counters();
  fmt::print(stderr, "\r  cycle {:>12}   rays done {:>10}   in flight {:>6}", c.cycles, c.rays, e.rays_in_flight());
}

ReplayStats run_cycle_mode(const ReplayArgs& a, const ReplayOptions& opt, TraceSource& source, const SceneAndBvh& sb,
                           std::ostream* hits, nlohmann::json& config, nlohmann::json& hw, std::string& table) {
  const hw::HwConfig cfg = hw::resolve_hw_config(a.method.config, a.preset);
  config["hw"] = hw::hw_config_json(cfg);
  source.set_triangle_count(sb.scene.size());
  hw::CycleRunOptions run;
  run.drive.vcd = a.vcd;
  run.drive.stop = &g_stop;
  const bool progress = !a.quiet && isatty(STDERR_FILENO);
  if (progress) run.drive.progress = print_progress;
  run.timeline = a.timeline;
  run.timeline_first = a.timeline_start;
  run.timeline_cycles = a.timeline_cycles;
  // Rays finish out of order; the hits file lists them in trace order, as the functional replay does.
  std::unique_ptr<hw::TraceOrderBuffer> ordered;
  if (hits) ordered = std::make_unique<hw::TraceOrderBuffer>(*hits);
  const hw::RayResultSink sink = [&ordered](const TraceRay& tr, const RayOutcome& out, uint64_t, uint64_t index) {
    ordered->put(index, hit_json_line(tr, out));
  };
  hw::CycleRunResult r = hw::run_cycle_replay([&source](TraceRay& tr) { return source.next(tr); }, sb.scene, sb.bvh,
                                              opt, cfg, hits ? sink : hw::RayResultSink{}, run);
  if (ordered) ordered->flush();  // a stopped run: the finished rays after the first dropped one
  if (progress) fmt::print(stderr, "\n");
  hw = std::move(r.hw);
  table = std::move(r.table);
  return r.stats;
}

int run_replay_command(const ReplayArgs& a) {
  if (a.mode != "functional" && a.mode != "cycle")
    throw std::runtime_error(fmt::format("option '--mode': '{}' is not available; modes: functional, cycle", a.mode));
  if (a.mode != "cycle" && (!a.preset.empty() || !a.vcd.empty() || !a.timeline.empty()))
    throw std::runtime_error("options '--preset', '--vcd' and '--timeline' need '--mode cycle'");
  const ReplayOptions opt = resolve_method_options(a.method);
  auto source = open_trace(a.trace);
  const SceneAndBvh sb = load_trace_scene(source->header());

  std::ofstream hits_file;
  if (!a.hits.empty()) {
    hits_file.open(a.hits);
    if (!hits_file) throw std::runtime_error(fmt::format("{}: cannot write hits file", a.hits));
  }
  nlohmann::json config = replay_config_json(opt);
  nlohmann::json hw;  // cycle mode: the hw section
  std::string table;
  g_stop = false;
  auto previous = std::signal(SIGINT, on_interrupt);
  std::ostream* hits = a.hits.empty() ? nullptr : &hits_file;
  ReplayStats stats;
  try {
    stats = a.mode == "cycle" ? run_cycle_mode(a, opt, *source, sb, hits, config, hw, table)
                              : run_replay(*source, sb, opt, hits, &g_stop);
  } catch (...) {
    std::signal(SIGINT, previous);
    throw;
  }
  std::signal(SIGINT, previous);

  if (!a.stats.empty()) {
    std::ofstream out(a.stats);
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write stats file", a.stats));
    config["trace"] = a.trace;
    config["scene"] = source->header().scene_path;
    config["triangles"] = sb.scene.size();
    nlohmann::json j = stats.to_json(config);
    if (!hw.is_null()) j["hw"] = std::move(hw);
    out << j.dump(2) << "\n";
  }
  if (!a.quiet) {
    fmt::print("vbsim replay {}  method {}  tester {}  scene {} ({} triangles)\n", a.trace,
               opt.method.name(), tester_name(opt.tester), source->header().scene, sb.scene.size());
    fmt::print("{}{}", stats.summary(), table);
  }
  return stats.partial ? 130 : 0;
}

}  // namespace

std::string default_trace_path() { return std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl"; }

void add_replay_command(CLI::App& app) {
  auto args = std::make_shared<ReplayArgs>();
  CLI::App* cmd = app.add_subcommand("replay", "replay a trace untimed and score every method's answer");
  cmd->add_option("trace", args->trace, "trace file (.jsonl text or .vbt binary)")->required();
  cmd->add_option("--mode", args->mode, "replay mode: functional (untimed) or cycle (the SystemC hardware model)")
      ->capture_default_str();
  cmd->add_option("--preset", args->preset, "cycle mode: hardware preset, small or large [the config's hw.preset, else small]");
  cmd->add_option("--vcd", args->vcd, "cycle mode: write a VCD of the key values here");
  cmd->add_option("--timeline", args->timeline, "cycle mode: write a Chrome trace-event JSON of a cycle window here");
  cmd->add_option("--timeline-start", args->timeline_start, "cycle mode: first cycle of the timeline window")
      ->capture_default_str();
  cmd->add_option("--timeline-cycles", args->timeline_cycles, "cycle mode: cycles in the timeline window")
      ->capture_default_str();
  cmd->add_option("--stats", args->stats, "write the statistics JSON here");
  cmd->add_option("--hits", args->hits, "write one JSON line per ray here");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  add_method_options(*cmd, args->method, "none");
  cmd->callback([args] {
    const int rc = run_replay_command(*args);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

int run_default_job() {
  ReplayArgs a;
  a.trace = default_trace_path();
  a.method.default_method = "validity-bit";
  const int rc = run_replay_command(a);
  print_tradeoff_table(a.trace);
  return rc;
}

}  // namespace vbsim::cli
