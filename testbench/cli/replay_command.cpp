// vbsim replay: functional replay of a trace, streamed.
#include <fmt/format.h>

#include <atomic>
#include <csignal>
#include <fstream>
#include <iostream>

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
  bool quiet = false;
  MethodOptions method;
};

int run_replay_command(const ReplayArgs& a) {
  if (a.mode != "functional")
    throw std::runtime_error(fmt::format("option '--mode': '{}' is not available; modes: functional", a.mode));
  const ReplayOptions opt = resolve_method_options(a.method);
  auto source = open_trace(a.trace);
  const SceneAndBvh sb = load_trace_scene(source->header());

  std::ofstream hits_file;
  if (!a.hits.empty()) {
    hits_file.open(a.hits);
    if (!hits_file) throw std::runtime_error(fmt::format("{}: cannot write hits file", a.hits));
  }
  g_stop = false;
  auto previous = std::signal(SIGINT, on_interrupt);
  const ReplayStats stats = run_replay(*source, sb, opt, a.hits.empty() ? nullptr : &hits_file, &g_stop);
  std::signal(SIGINT, previous);

  if (!a.stats.empty()) {
    std::ofstream out(a.stats);
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write stats file", a.stats));
    nlohmann::json config = replay_config_json(opt);
    config["trace"] = a.trace;
    config["scene"] = source->header().scene_path;
    config["triangles"] = sb.scene.size();
    out << stats.to_json(config).dump(2) << "\n";
  }
  if (!a.quiet) {
    fmt::print("vbsim replay {}  method {}  tester {}  scene {} ({} triangles)\n", a.trace,
               opt.method.name(), tester_name(opt.tester), source->header().scene, sb.scene.size());
    fmt::print("{}", stats.summary());
  }
  return stats.partial ? 130 : 0;
}

}  // namespace

std::string default_trace_path() { return std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl"; }

void add_replay_command(CLI::App& app) {
  auto args = std::make_shared<ReplayArgs>();
  CLI::App* cmd = app.add_subcommand("replay", "replay a trace untimed and score every method's answer");
  cmd->add_option("trace", args->trace, "trace file (.jsonl text or .vbt binary)")->required();
  cmd->add_option("--mode", args->mode, "replay mode: functional")->capture_default_str();
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
  return run_replay_command(a);
}

}  // namespace vbsim::cli
