// vbsim score: every scenario family replayed with every method and tester, in
// process; a table of verdict rates with 95% intervals (model/score/).
#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <thread>

#include "commands.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "replay/replay_config.h"
#include "score/score_run.h"
#include "score/score_table.h"

namespace vbsim::cli {

namespace {

struct ScoreArgs {
  std::vector<std::string> paths;
  std::string methods, testers = "three-half-plane,moller-trumbore";
  std::string out, markdown, regenerate;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  bool quiet = false;
  int64_t parent_window = ParentRayStore::kDefaultWindow;
};

std::vector<TesterKind> parse_testers(const std::string& list) {
  std::vector<TesterKind> out;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    TesterKind t;
    if (!parse_tester(name, t))
      throw ConfigError(fmt::format("option '--testers': unknown tester '{}' (three-half-plane, moller-trumbore)", name));
    out.push_back(t);
  }
  if (out.empty()) throw ConfigError("option '--testers': empty list");
  return out;
}

std::string joined_default_methods() {
  std::string s;
  for (const std::string& m : default_score_methods()) s += (s.empty() ? "" : ",") + m;
  return s;
}

void print_summary(const nlohmann::json& score) {
  fmt::print("{:<14} {:<48} {:<17} {:>9} {:>10} {:>10} {:>10} {:>10}\n", "family", "method", "tester",
             "rays", "self_hit/M", "false/M", "missed/M", "rays/s");
  for (const auto& r : score["rows"]) {
    if (r["kind"] != "all") continue;
    const auto& pm = r["per_million"];
    fmt::print("{:<14} {:<48} {:<17} {:>9} {:>10} {:>10} {:>10} {:>10.0f}\n", r["family"].get<std::string>(),
               r["method"].get<std::string>(), r["tester"].get<std::string>(), r["rays"].get<uint64_t>(),
               format_per_million(pm["self_hit"]["rate"].get<double>()),
               format_per_million(pm["false_hit"]["rate"].get<double>()),
               format_per_million(pm["missed"]["rate"].get<double>()), r["rays_per_s"].get<double>());
  }
}

void run_score_command(const ScoreArgs& a) {
  if (a.threads < 1) throw ConfigError("option '--threads': must be >= 1");
  const std::vector<MethodSpec> methods =
      parse_method_list(a.methods.empty() ? joined_default_methods() : a.methods);
  const std::vector<TesterKind> testers = parse_testers(a.testers);
  const std::vector<ScoreFamily> families = collect_score_families(a.paths);
  std::vector<NamedPath> inputs;
  for (const ScoreFamily& f : families)
    for (const std::string& t : f.traces) inputs.push_back({"trace", t});
  check_output_paths(inputs, {{"option '--out'", a.out}, {"option '--accuracy-md'", a.markdown}});

  std::string command = "vbsim score";
  for (const std::string& p : a.paths) command += " " + p;
  if (!a.methods.empty()) command += " --methods " + a.methods;
  command += " --testers " + a.testers;

  const std::vector<ScoreCell> cells =
      run_score(families, score_configs(methods, testers), a.threads, a.parent_window);
  const nlohmann::json score = score_json(families, cells, command);
  if (!a.out.empty()) write_output_file(a.out, score.dump(1) + "\n", "score JSON");
  if (!a.markdown.empty())
    write_output_file(a.markdown, score_markdown(score, a.regenerate.empty() ? command : a.regenerate), "markdown");
  if (!a.quiet) print_summary(score);
}

}  // namespace

void add_score_command(CLI::App& app) {
  auto args = std::make_shared<ScoreArgs>();
  CLI::App* cmd = app.add_subcommand(
      "score", "replay scenario traces with every method and tester; verdict rates with 95% intervals");
  cmd->add_option("paths", args->paths,
                  "scenario directories (each a family: its .jsonl/.vbt traces) or trace files")
      ->required();
  cmd->add_option("--methods", args->methods,
                  "comma list of METHOD[+METHOD][:KEY=VALUE...], KEY a replay option without dashes "
                  "(e.g. validity-bit:vb-eps-mode=fixed:vb-eps=1e-4) [" + joined_default_methods() + "]");
  cmd->add_option("--testers", args->testers, "comma list of testers")->capture_default_str();
  cmd->add_option("--out", args->out, "write the score table as JSON here");
  cmd->add_option("--accuracy-md", args->markdown, "write the markdown table here (docs/results/accuracy.md)");
  cmd->add_option("--regenerate-with", args->regenerate,
                  "the command the markdown names for regenerating it [this score command]");
  cmd->add_option("--threads", args->threads, "worker threads")->capture_default_str();
  add_parent_window_option(*cmd, args->parent_window);
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args] { run_score_command(*args); });
}

}  // namespace vbsim::cli
