// vbsim score: every scenario family replayed with every method and tester, in
// process; a table of verdict rates with 95% intervals (model/score/).
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "commands.h"
#include "tech_option.h"
#include "threads_option.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "exit_codes.h"
#include "method_options.h"
#include "output_provenance.h"
#include "progress/progress_meter.h"
#include "provenance/provenance.h"
#include "score_merge.h"
#include "trace/trace_file.h"
#include "trace/trace_ray_count.h"
#include "replay/replay_config.h"
#include "score/score_markdown.h"
#include "score/score_run.h"
#include "score/score_table.h"
#include "score/tradeoff_table.h"

namespace vbsim::cli {

namespace {

struct ScoreArgs {
  std::vector<std::string> paths;
  std::string methods, testers = "three-half-plane,moller-trumbore";
  std::string out, markdown, regenerate;
  int threads = 1;  // --threads (every core by default)
  bool quiet = false;
  int64_t parent_window = ParentRayStore::kDefaultWindow;
  bool score_incomplete = false;
  bool merge = false;
  bool testers_given = false;
  std::string mode = "functional", preset, cycle_testers;
  std::string tech;  // --tech FILE (empty: the shipped default)
};


/// Every column named with its unit: the model's cycles per ray, energy per ray
/// (operations, memory, leakage) and chip area (cycle mode), and the host's
/// functional replay speed.
void print_summary(const nlohmann::json& score) {
  const std::vector<TradeoffRow> rows = tradeoff_rows(score);
  const bool cycles = std::any_of(rows.begin(), rows.end(), [](const TradeoffRow& r) { return r.has_cycles; });
  const bool costs = std::any_of(rows.begin(), rows.end(), [](const TradeoffRow& r) { return r.has_cycle_energy; });
  std::string head = fmt::format("{:<22} {:<44} {:<16} {:>14} {:>12} {:>13}", "family", "method", "tester",
                                 "secondary rays", "sec. err/M", "camera miss/M");
  if (cycles) head += fmt::format(" {:>10}", "cycles/ray");
  if (costs) head += fmt::format(" {:>10} {:>9}", "pJ/ray", "chip mm2");
  fmt::print("{} {:>12}\n", head, "host rays/s");
  for (const TradeoffRow& r : rows) {
    std::string line = fmt::format("{:<22} {:<44} {:<16} {:>14} {:>12} {:>13}", r.family, r.method, r.tester,
                                   r.secondary_scored, format_per_million(r.secondary_rate),
                                   format_per_million(r.camera_miss_rate));
    if (cycles) line += fmt::format(" {:>10}", r.has_cycles ? fmt::format("{:.3g}", r.cycles_per_ray) : "");
    if (costs)
      line += r.has_cycle_energy ? fmt::format(" {:>10.5g} {:>9.4f}", r.cycle_energy_per_ray_pj, r.chip_mm2)
                                 : fmt::format(" {:>10} {:>9}", "", "");
    fmt::print("{} {:>12.0f}\n", line, r.rays_per_s);
  }
  for (const auto& row : score["rows"])
    if (costs && row.contains("cycle") && row["cycle"].contains("tech")) {
      fmt::print("pJ/ray: the cycle-level model's energy per ray (operations, memory, leakage), {} preset, priced by "
                 "{}; host rays/s: the functional replay on this machine\n",
                 row["cycle"]["preset"].get<std::string>(), row["cycle"]["tech"].get<std::string>());
      break;
    }
}

/// Writes the table (JSON, markdown) and prints its summary.
void write_outputs(const ScoreArgs& a, nlohmann::json score, const std::string& command,
                   const std::vector<std::string>& inputs) {
  score["provenance"] = provenance_json(inputs);
  if (!a.out.empty()) write_output_file(a.out, score.dump(1) + "\n", "score JSON");
  if (!a.markdown.empty())
    write_output_file(a.markdown,
               score_markdown(score, a.regenerate.empty() ? command : a.regenerate) +
                   markdown_provenance(score["provenance"]),
               "markdown");
  if (!a.quiet) print_summary(score);
}

void run_score_command(const ScoreArgs& a) {
  check_threads_option(a.threads);
  if (a.mode != "functional" && a.mode != "cycle")
    throw UsageError(fmt::format("option '--mode': '{}' is not a mode (functional, cycle)", a.mode));
  if (a.mode != "cycle" && (!a.preset.empty() || !a.cycle_testers.empty()))
    throw UsageError("options '--preset' and '--cycle-testers' need '--mode cycle'");
  check_preset_name(a.preset);
  std::string command = "vbsim score";
  for (const std::string& p : a.paths) command += " " + p;
  if (a.merge) {
    if (!a.methods.empty() || a.testers_given)
      throw UsageError("option '--merge' takes score tables; their runs chose the methods and testers");
    // Before any work: no output may overwrite a table it merges.
    std::vector<NamedPath> tables;
    for (const std::string& p : a.paths) tables.push_back({"score table", p});
    check_output_paths(tables, {{"option '--out'", a.out}, {"option '--accuracy-md'", a.markdown}});
    write_outputs(a, merge_score_tables(a.paths, command + " --merge"), command + " --merge", a.paths);
    return;
  }
  std::vector<MethodSpec> methods;
  try {
    methods = parse_method_list(a.methods.empty() ? default_score_method_list() : a.methods);
  } catch (const ConfigError& e) {
    throw UsageError(std::string("option '--methods': ") + e.what());
  }
  const std::vector<TesterKind> testers = parse_tester_list(a.testers);
  const std::vector<ScoreFamily> families = collect_score_families(a.paths);
  std::vector<NamedPath> named_inputs;
  // Before any work: no output may overwrite a trace, its scene or the technology file.
  for (const ScoreFamily& f : families)
    for (const std::string& t : f.traces) {
      named_inputs.push_back({"trace", t});
      named_inputs.push_back({"scene of " + t, open_trace(t)->header().scene_path});
    }
  named_inputs.push_back({"option '--tech'", a.tech});
  check_output_paths(named_inputs, {{"option '--out'", a.out}, {"option '--accuracy-md'", a.markdown}});
  const TechFile tech = resolve_tech(a.tech);
  if (!a.tech.empty()) command += " --tech " + a.tech;

  if (!a.methods.empty()) command += " --methods " + a.methods;
  command += " --testers " + a.testers;
  ScoreRunOptions run;
  run.threads = a.threads;
  run.tech = &tech;
  if (a.mode == "cycle") {
    run.cycle = true;
    run.hw = hw::resolve_hw_config("", a.preset);
    run.cycle_testers = a.cycle_testers.empty() ? testers : parse_tester_list(a.cycle_testers, "--cycle-testers");
    command += " --mode cycle --preset " + run.hw.preset;
    if (!a.cycle_testers.empty()) command += " --cycle-testers " + a.cycle_testers;
  }

  std::vector<std::string> inputs;
  uint64_t total = 0;
  std::FILE* terminal = ProgressMeter::terminal_or_null(a.quiet);
  for (const ScoreFamily& fam : families)
    for (const std::string& t : fam.traces) {
      inputs.push_back(t);
      if (terminal) total += count_trace_rays(t);
    }
  std::vector<ScoreConfig> configs = score_configs(methods, testers);
  for (ScoreConfig& c : configs) c.options.score_incomplete = a.score_incomplete;
  ProgressMeter meter(fmt::format("score: {} configurations", configs.size()), total, "rays", terminal);
  run.progress = [&meter](uint64_t n) { meter.add(n); };
  run.parent_window = a.parent_window;
  const std::vector<ScoreCell> cells = run_score(families, configs, run);
  meter.finish();
  inputs.push_back(tech.path);
  write_outputs(a, score_json(families, cells, command, &tech), command, inputs);
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
                  "(e.g. validity-bit:vb-eps-mode=fixed:vb-eps=1e-4) [" + default_score_method_list() + "]");
  CLI::Option* testers = cmd->add_option("--testers", args->testers, "comma list of testers")->capture_default_str();
  cmd->add_option("--out", args->out, "write the score table as JSON here");
  cmd->add_option("--accuracy-md", args->markdown, "write the markdown table here (docs/results/accuracy.md)");
  cmd->add_option("--regenerate-with", args->regenerate,
                  "the command the markdown names for regenerating it [this score command]");
  add_threads_option(*cmd, args->threads, "worker threads of the functional replays");
  cmd->add_option("--mode", args->mode,
                  "functional, or cycle: also every configuration's cycles per ray and rays per cycle from the "
                  "cycle-level model on the same traces (one replay at a time)")
      ->capture_default_str();
  cmd->add_option("--preset", args->preset, "cycle mode: hardware preset, small, large or rtcore [small]");
  add_tech_option(*cmd, args->tech);
  cmd->add_option("--cycle-testers", args->cycle_testers,
                  "cycle mode: the testers whose configurations are timed [every tester of --testers]");
  add_parent_window_option(*cmd, args->parent_window);
  add_score_incomplete_option(*cmd, args->score_incomplete);
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->add_flag("--merge", args->merge,
                "the paths are score tables (--out JSON) of runs over disjoint families: write their union");
  cmd->callback([args, testers] {
    args->testers_given = testers->count() > 0;
    run_score_command(*args);
  });
}

}  // namespace vbsim::cli
