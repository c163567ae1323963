// vbsim bench: vbsim's functional (or cycle-level) replay against Embree on the
// same rays and scene, in one run: random camera-like rays, or a captured
// trace's rays (--trace) over the trace's scene. Where the two answer a ray
// differently, the exact oracle says which is right.
#include <fmt/format.h>

#include <algorithm>
#include <fstream>

#include "progress/work_progress.h"
#include "bench/cycle_bench.h"
#include "bench/functional_bench.h"
#include "commands.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "exit_codes.h"
#include "provenance/provenance.h"
#include "method_options.h"
#include "threads_option.h"
#include "replay/replay_run.h"
#include "replay/replay_stats.h"
#include "trace/checked_trace_source.h"
#include "trace/trace_file.h"

namespace vbsim::cli {

namespace {

struct BenchArgs {
  std::string mode = "functional";
  std::string scene = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj";
  bool scene_given = false;
  std::string trace;  // the rays and the scene of a trace instead of random rays
  int64_t rays = 200000;
  bool rays_given = false;  // with --trace: the first N rays (default: all)
  uint64_t seed = 1;
  bool seed_given = false;
  int repeats = 3;
  std::string json;
  std::string preset;  // cycle mode
  std::string embree_accel;
  bool quiet = false;
  int threads = all_cores();  // functional mode: also timed on this many threads when above 1
  bool threads_given = false;
  MethodOptions method;
};

/// One line per class that occurred, e.g. "12 ties at equal t (both right), 7 Embree wrong".
std::string disagreement_text(const DisagreementReport& d) {
  static const char* const kWords[kDisagreementClassCount] = {
      "ties at equal t (both right)", "Embree wrong", "vbsim wrong", "both wrong",
      "changed by the method (not the same query)"};
  std::string s;
  for (int k = 0; k < kDisagreementClassCount; ++k) {
    const auto c = static_cast<DisagreementClass>(k);
    if (d.count(c) == 0 && c != DisagreementClass::VbsimWrong) continue;  // vbsim's count always shows
    s += fmt::format("{}{} {}", s.empty() ? "" : ", ", d.count(c), kWords[k]);
    const int64_t own = d.at_parent[static_cast<size_t>(k)];
    if (own > 0) s += fmt::format(" ({} on the ray's own parent triangle)", own);
  }
  return s;
}

void run_bench(const BenchArgs& a) {
  if (a.mode != "functional" && a.mode != "cycle")
    throw UsageError(fmt::format("option '--mode': '{}' is not available; modes: functional, cycle", a.mode));
  if (a.rays <= 0) throw UsageError("option '--rays': must be > 0");
  if (a.repeats <= 0) throw UsageError("option '--repeats': must be > 0");
  if (a.mode != "cycle" && !a.preset.empty()) throw UsageError("option '--preset' needs '--mode cycle'");
  if (!a.trace.empty() && a.scene_given)
    throw UsageError("options '--trace' and '--scene' exclude each other: a trace's scene is the one its header names");
  if (!a.trace.empty() && a.seed_given) throw UsageError("option '--seed' is for random rays, not '--trace'");
  if (a.threads < 1) throw UsageError("option '--threads': must be >= 1");
  if (a.threads_given && a.mode == "cycle")
    throw UsageError("option '--threads': functional mode only (the cycle-level model runs on one thread)");
  check_preset_name(a.preset);
  const ReplayOptions opt = resolve_method_options(a.method);
  std::unique_ptr<TraceSource> file;
  if (!a.trace.empty()) file = open_trace(a.trace);  // names the file and field of a bad header
  const std::string scene_path = file ? file->header().scene_path : a.scene;
  check_output_paths({{file ? "trace" : "option '--scene'", file ? a.trace : a.scene},
                      {"scene", file ? scene_path : ""},
                      {"option '--config'", a.method.config}},
                     {{"option '--json'", a.json}});
  Scene scene;
  BenchWorkload w;
  MeterWorkProgress loading("scene", ProgressMeter::terminal_or_null(a.quiet));
  if (file) {
    if (file->header().triangle_masks)
      throw std::runtime_error(fmt::format("{}: header: field 'triangle_masks': the bench times Embree without ray "
                                           "masks, so a trace with masks cannot be compared with it (replay it)",
                                           a.trace));
    try {
      scene = load_scene(scene_path, file->header().transform, &loading);
    } catch (const SceneError& e) {
      throw SceneError(fmt::format("{}: header: field 'scene': {}", a.trace, e.what()));
    }
    TraceConsistencyChecker::Options checks;  // children after parents, prims in range
    checks.triangles = &scene.triangles;
    checks.window = static_cast<std::size_t>(opt.parent_window);
    CheckedTraceSource source(*file, checks);
    w = trace_workload(source, scene, opt, a.rays_given ? a.rays : -1);
    if (w.size() == 0) throw std::runtime_error(fmt::format("{}: the trace has no rays to time", a.trace));
  } else {
    scene = load_scene(scene_path, std::nullopt, &loading);
    w = random_workload(scene, opt, a.rays, a.seed);
  }
  loading.finish();
  BenchParams p;
  p.repeats = a.repeats;
  p.embree_accel = a.embree_accel;
  p.threads = a.mode == "cycle" ? 1 : a.threads;
  nlohmann::json j;
  BenchResult r;
  if (a.mode == "cycle") {
    const hw::HwConfig cfg = hw::resolve_hw_config(a.method.config, a.preset);
    const CycleBenchResult c = run_cycle_bench(scene, opt, cfg, w, p);
    r = c.speed;
    j = r.to_json();
    j["hw"] = {{"config", hw::hw_config_json(hw::for_tester(cfg, opt.tester))},
               {"cycles", c.cycles},
               {"rays_per_cycle", c.rays_per_cycle},
               {"energy", c.energy},
               {"area", c.area}};
    if (!a.quiet)
      fmt::print("cycle-level model: {} preset, {} cycles, {:.4f} rays/cycle\n", cfg.preset, c.cycles,
                 c.rays_per_cycle);
  } else {
    r = run_functional_bench(scene, opt, w, p);
    j = r.to_json();
  }
  j["mode"] = a.mode;
  j["workload"] = file ? "trace" : "random";
  j["trace"] = file ? nlohmann::json(a.trace) : nlohmann::json();
  j["scene"] = scene_path;
  j["triangles"] = scene.size();
  j["seed"] = file ? nlohmann::json() : nlohmann::json(a.seed);
  j["repeats"] = a.repeats;
  j["embree_accel"] = a.embree_accel.empty() ? "default" : a.embree_accel;
  j["config"] = replay_config_json(opt);
  j["provenance"] = file ? provenance_json({a.trace, scene_path, a.method.config})
                         : provenance_json({a.scene, a.method.config});
  if (!a.json.empty()) write_output_file(a.json, j.dump(2) + "\n", "bench JSON");
  if (a.quiet) return;
  const std::string what = file ? fmt::format("{} rays of {}", r.rays, a.trace) : fmt::format("{} rays", r.rays);
  fmt::print("vbsim bench ({}, {}, {} triangles, method {}, tester {}, best of {})\n", a.mode, what,
             scene.size(), opt.method.name(), tester_name(opt.tester), a.repeats);
  fmt::print("  vbsim   {:>12.0f} rays/s   ({} hits)\n", r.vbsim_rays_per_s, r.vbsim_hits);
  fmt::print("  embree  {:>12.0f} rays/s   ({} hits{})\n", r.embree_rays_per_s, r.embree_hits,
             a.embree_accel.empty() ? "" : ", tri_accel " + a.embree_accel);
  const bool shadows = std::find(w.any_hit.begin(), w.any_hit.end(), 1) != w.any_hit.end();
  fmt::print("  ratio   {:>12.3f}          (same {} on {} of {} rays{})\n", r.ratio, shadows ? "answer" : "triangle",
             r.same_prim, r.rays, shadows ? "; shadow rays: occluded alike" : "");
  const DisagreementReport& d = r.disagreements;
  if (d.total() > 0) {
    fmt::print("  differ  {} ray{}, by the exact oracle: {}\n", d.total(), d.total() == 1 ? "" : "s",
               disagreement_text(d));
    int shown = 0;
    for (const BenchDisagreement& x : d.rays) {
      if (x.cls != DisagreementClass::VbsimWrong && x.cls != DisagreementClass::BothWrong) continue;
      if (++shown > 5) break;
      fmt::print("          {} ray at index {} (id {}): vbsim {}, Embree {}{}\n", disagreement_class_name(x.cls),
                 x.index, x.id, x.vbsim, x.embree == kEmbreeOccluded ? "occluded" : std::to_string(x.embree),
                 x.at_parent ? ", at its parent triangle" : "");
    }
  }
  fmt::print("  vbsim work per ray: {:.1f} node fetches, {:.1f} box tests, {:.1f} triangle tests\n",
             r.node_fetches_per_ray, r.box_tests_per_ray, r.triangle_tests_per_ray);
  const ThreadedBench& t = r.threaded;
  if (t.threads <= 1) return;
  fmt::print("on {} threads (each ray replayed on its own; best of {}):\n", t.threads, a.repeats);
  fmt::print("  vbsim   {:>12.0f} rays/s   ({:.2f}x one thread)\n", t.vbsim_rays_per_s,
             t.vbsim_rays_per_s / r.vbsim_rays_per_s);
  fmt::print("  embree  {:>12.0f} rays/s   ({:.2f}x one thread)\n", t.embree_rays_per_s,
             t.embree_rays_per_s / r.embree_rays_per_s);
  fmt::print("  ratio   {:>12.3f}          (answers as on one thread: {})\n", t.ratio,
             t.vbsim_differ + t.embree_differ == 0
                 ? std::string("all")
                 : fmt::format("{} of vbsim's and {} of Embree's differ", t.vbsim_differ, t.embree_differ));
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "time vbsim against Embree on the same rays (one thread; functional mode on every core too)");
  CLI::Option* trace = cmd->add_option("--trace", args->trace,
                                       "time the rays of this trace (.jsonl or .vbt) over its header's scene "
                                       "instead of random rays");
  cmd->add_option("--mode", args->mode, "what to time: functional or cycle")->capture_default_str();
  cmd->add_option("--preset", args->preset, "cycle mode: hardware preset [the config's hw.preset, else small]");
  CLI::Option* scene = cmd->add_option("--scene", args->scene, "scene file for random rays")->capture_default_str();
  CLI::Option* rays =
      cmd->add_option("--rays", args->rays, "number of random rays; with --trace, the first N rays [all]")
          ->capture_default_str();
  CLI::Option* seed = cmd->add_option("--seed", args->seed, "random seed")->capture_default_str();
  cmd->add_option("--repeats", args->repeats, "timed repetitions; the best counts")->capture_default_str();
  cmd->add_option("--json", args->json, "write the results JSON here");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->add_option("--embree-accel", args->embree_accel,
                  "Embree's triangle acceleration structure to time against (its tri_accel setting, e.g. "
                  "bvh4.triangle4v for a 4-wide tree) [Embree's choice for the host: bvh8.triangle4v with AVX]");
  CLI::Option* threads = cmd->add_option("--threads", args->threads,
                  "functional mode: also time both on this many threads (1: one thread only; the cycle-level "
                  "model runs on one) [every core]");
  add_method_options(*cmd, args->method, "none");
  (void)trace;
  cmd->callback([args, scene, rays, seed, threads] {
    args->threads_given = threads->count() > 0;
    args->scene_given = scene->count() > 0;
    args->rays_given = rays->count() > 0;
    args->seed_given = seed->count() > 0;
    run_bench(*args);
  });
}

}  // namespace vbsim::cli
