// vbsim gen: writes a scenario's trace, with `expect` filled in by the oracle.
#include <fmt/format.h>

#include <filesystem>

#include "commands.h"
#include "exact/expected_answers.h"
#include "gen/paths_generator.h"
#include "trace/trace_file.h"
#include "trace/trace_header_json.h"

namespace vbsim::cli {

namespace fs = std::filesystem;

namespace {

struct GenArgs {
  std::string scenario;
  std::string scene = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj";
  int paths = 200;
  int depth = 3;
  uint64_t seed = 1;
  std::string out_dir;
  std::string name;
};

void run_gen(const GenArgs& a) {
  if (a.scenario != "paths")
    throw std::runtime_error(fmt::format("unknown scenario '{}'; scenarios: paths", a.scenario));
  if (a.paths <= 0) throw std::runtime_error("option '--rays': must be > 0");
  if (a.depth < 0) throw std::runtime_error("option '--depth': must be >= 0");
  const Scene scene = load_scene(a.scene);
  const Bvh bvh = build_bvh(scene);
  PathsParams p;
  p.paths = a.paths;
  p.max_depth = a.depth;
  p.seed = a.seed;
  GeneratedPaths g = generate_paths(scene, bvh, p);

  fs::create_directories(a.out_dir);
  const fs::path out = fs::path(a.out_dir) / (a.name.empty() ? a.scenario + ".jsonl" : a.name);
  TraceHeader h;
  h.scene = scene_relative_to(a.scene, out.string());
  h.light = g.light;
  h.generator = fmt::format("vbsim gen paths --rays {} --depth {} --seed {}", a.paths, a.depth, a.seed);
  h.description = fmt::format(
      "{} camera paths over {}: primary, shadow, reflect, refract and diffuse rays; hit points by ray "
      "equation on even paths, barycentric on odd ones; expect from the exact oracle",
      a.paths, fs::path(a.scene).filename().string());
  auto sink = create_trace_writer(out.string(), h);
  fill_expect(g.rays, scene, bvh);
  for (const TraceRay& tr : g.rays) sink->write(tr);
  sink->close();
  fmt::print("vbsim gen {}: {} rays -> {}\n", a.scenario, g.rays.size(), out.string());
}

}  // namespace

void add_gen_command(CLI::App& app) {
  auto args = std::make_shared<GenArgs>();
  CLI::App* cmd = app.add_subcommand("gen", "generate a scenario's scene trace with exact expectations");
  cmd->add_option("scenario", args->scenario, "scenario: paths")->required();
  cmd->add_option("--scene", args->scene, "mesh the paths run over")->capture_default_str();
  cmd->add_option("--rays", args->paths, "camera paths (each emits several rays)")->capture_default_str();
  cmd->add_option("--depth", args->depth, "hits per path at most")->capture_default_str();
  cmd->add_option("--seed", args->seed, "random seed")->capture_default_str();
  cmd->add_option("--name", args->name, "output file name [SCENARIO.jsonl]");
  cmd->add_option("-o,--out", args->out_dir, "output directory")->required();
  cmd->callback([args] { run_gen(*args); });
}

}  // namespace vbsim::cli
