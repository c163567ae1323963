// vbsim bench: vbsim's functional replay against Embree's rtcIntersect1 on the
// same rays and scene, in one run.
#include <fmt/format.h>

#include <fstream>

#include "bench/cycle_bench.h"
#include "bench/functional_bench.h"
#include "commands.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "exit_codes.h"
#include "provenance/provenance.h"
#include "method_options.h"
#include "replay/replay_stats.h"

namespace vbsim::cli {

namespace {

struct BenchArgs {
  std::string mode = "functional";
  std::string scene = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj";
  int64_t rays = 200000;
  uint64_t seed = 1;
  int repeats = 3;
  std::string json;
  std::string preset;  // cycle mode
  std::string embree_accel;
  bool quiet = false;
  MethodOptions method;
};

void run_bench(const BenchArgs& a) {
  if (a.mode != "functional" && a.mode != "cycle")
    throw UsageError(fmt::format("option '--mode': '{}' is not available; modes: functional, cycle", a.mode));
  if (a.rays <= 0) throw UsageError("option '--rays': must be > 0");
  if (a.repeats <= 0) throw UsageError("option '--repeats': must be > 0");
  if (a.mode != "cycle" && !a.preset.empty()) throw UsageError("option '--preset' needs '--mode cycle'");
  check_preset_name(a.preset);
  check_output_paths({{"option '--scene'", a.scene}, {"option '--config'", a.method.config}},
                     {{"option '--json'", a.json}});
  const ReplayOptions opt = resolve_method_options(a.method);
  const Scene scene = load_scene(a.scene);
  BenchParams p;
  p.rays = a.rays;
  p.seed = a.seed;
  p.repeats = a.repeats;
  p.embree_accel = a.embree_accel;
  nlohmann::json j;
  BenchResult r;
  if (a.mode == "cycle") {
    const hw::HwConfig cfg = hw::resolve_hw_config(a.method.config, a.preset);
    const CycleBenchResult c = run_cycle_bench(scene, opt, cfg, p);
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
    r = run_functional_bench(scene, opt, p);
    j = r.to_json();
  }
  j["mode"] = a.mode;
  j["scene"] = a.scene;
  j["triangles"] = scene.size();
  j["seed"] = a.seed;
  j["repeats"] = a.repeats;
  j["embree_accel"] = a.embree_accel.empty() ? "default" : a.embree_accel;
  j["config"] = replay_config_json(opt);
  j["provenance"] = provenance_json({a.scene, a.method.config});
  if (!a.json.empty()) write_output_file(a.json, j.dump(2) + "\n", "bench JSON");
  if (a.quiet) return;
  fmt::print("vbsim bench ({}, {} rays, {} triangles, method {}, tester {}, best of {})\n", a.mode,
             r.rays, scene.size(), opt.method.name(), tester_name(opt.tester), a.repeats);
  fmt::print("  vbsim   {:>12.0f} rays/s   ({} hits)\n", r.vbsim_rays_per_s, r.vbsim_hits);
  fmt::print("  embree  {:>12.0f} rays/s   ({} hits{})\n", r.embree_rays_per_s, r.embree_hits,
             a.embree_accel.empty() ? "" : ", tri_accel " + a.embree_accel);
  fmt::print("  ratio   {:>12.3f}          (same triangle on {} of {} rays)\n", r.ratio, r.same_prim, r.rays);
  fmt::print("  vbsim work per ray: {:.1f} node fetches, {:.1f} box tests, {:.1f} triangle tests\n",
             r.node_fetches_per_ray, r.box_tests_per_ray, r.triangle_tests_per_ray);
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand("bench", "time vbsim against Embree on the same rays (single thread)");
  cmd->add_option("--mode", args->mode, "what to time: functional or cycle")->capture_default_str();
  cmd->add_option("--preset", args->preset, "cycle mode: hardware preset [the config's hw.preset, else small]");
  cmd->add_option("--scene", args->scene, "scene file")->capture_default_str();
  cmd->add_option("--rays", args->rays, "number of random rays")->capture_default_str();
  cmd->add_option("--seed", args->seed, "random seed")->capture_default_str();
  cmd->add_option("--repeats", args->repeats, "timed repetitions; the best counts")->capture_default_str();
  cmd->add_option("--json", args->json, "write the results JSON here");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->add_option("--embree-accel", args->embree_accel,
                  "Embree's triangle acceleration structure to time against (its tri_accel setting, e.g. "
                  "bvh4.triangle4v for a 4-wide tree) [Embree's choice for the host: bvh8.triangle4v with AVX]");
  add_method_options(*cmd, args->method, "none");
  cmd->callback([args] { run_bench(*args); });
}

}  // namespace vbsim::cli
