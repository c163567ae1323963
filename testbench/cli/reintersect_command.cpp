// vbsim reintersect: pbrt-v4's Triangle Reintersect protocol in process,
// streamed (model/score/reintersect_run.h): re-hit rates of every method and
// tester at pbrt's size or larger, without writing a trace.
#include <fmt/format.h>

#include <thread>

#include "commands.h"
#include "exit_codes.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "method_options.h"
#include "replay/replay_config.h"
#include "score/reintersect_run.h"

namespace vbsim::cli {

namespace {

struct ReintersectArgs {
  ReintersectParams params;
  std::string methods = "offset-errbound", testers = "pbrt-watertight,three-half-plane";
  std::string json, markdown;
  bool quiet = false;
};

void run(ReintersectArgs a) {
  if (a.params.triangles < 1) throw UsageError("option '--triangles': must be >= 1");
  if (a.params.children < 0 || a.params.children > 1000000)
    throw UsageError("option '--children': must lie in [0, 1000000]");
  if (a.params.threads < 1) throw UsageError("option '--threads': must be >= 1");
  if (!(a.params.exp >= 0 && a.params.exp <= 30)) throw UsageError("option '--exp': must lie in [0, 30]");
  const std::vector<ScoreConfig> configs =
      score_configs(parse_method_list(a.methods), parse_tester_list(a.testers, "--testers"));
  const std::string command =
      fmt::format("vbsim reintersect --triangles {} --first {} --children {} --methods {} --testers {}",
                  a.params.triangles, a.params.first, a.params.children, a.methods, a.testers);
  check_output_paths({}, {{"option '--json'", a.json}, {"option '--markdown'", a.markdown}});
  const ReintersectResult r = run_reintersect(a.params, configs);
  const nlohmann::json j = reintersect_json(r, command);
  if (!a.json.empty()) write_output_file(a.json, j.dump(1) + "\n", "reintersect JSON");
  if (!a.markdown.empty()) write_output_file(a.markdown, reintersect_markdown(j), "reintersect markdown");
  if (a.quiet) return;
  fmt::print("{}\n{}", command, reintersect_markdown(j));
  fmt::print("{:.1f} s wall\n", r.wall_s);
}

}  // namespace

void add_reintersect_command(CLI::App& app) {
  auto args = std::make_shared<ReintersectArgs>();
  args->params.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  CLI::App* cmd = app.add_subcommand(
      "reintersect", "pbrt-v4's Triangle Reintersect protocol in process: re-hit rates with 95% intervals");
  cmd->add_option("--triangles", args->params.triangles, "triangles (pbrt-v4's test: 1000)")->capture_default_str();
  cmd->add_option("--first", args->params.first, "first triangle index, pbrt's RNG sequence")->capture_default_str();
  cmd->add_option("--children", args->params.children, "SpawnRay and SpawnRayTo children per triangle, each")
      ->capture_default_str();
  cmd->add_option("--exp", args->params.exp, "coordinates 10^U[-exp, exp]")->capture_default_str();
  cmd->add_option("--methods", args->methods, "comma list of methods, as for vbsim score")->capture_default_str();
  cmd->add_option("--testers", args->testers, "comma list of testers")->capture_default_str();
  cmd->add_option("--threads", args->params.threads, "worker threads")->capture_default_str();
  cmd->add_option("--json", args->json, "write the counts and rates as JSON here");
  cmd->add_option("--markdown", args->markdown, "write the table as markdown here");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args] { run(*args); });
}

}  // namespace vbsim::cli
