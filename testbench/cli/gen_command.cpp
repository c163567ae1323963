// vbsim gen: writes a scenario's scenes and traces, with `expect` filled in by
// the exact oracle (model/gen/scenario.h), into a directory it owns the files
// of (gen_directory.h).
#include <fmt/format.h>

#include <filesystem>
#include <map>

#include "commands.h"
#include "io/atomic_output_file.h"
#include "exit_codes.h"
#include "gen/scenario.h"
#include "gen_directory.h"
#include "progress/progress_meter.h"
#include "provenance/provenance.h"
#include "scene/scene.h"

namespace vbsim::cli {

namespace {

struct GenArgs {
  std::string scenario;
  int64_t rays = 200;
  uint64_t seed = 1;
  bool seed_given = false;  // --seed on the command line
  std::vector<std::string> set;
  std::string out_dir;
  bool quiet = false;
};

void run_gen(const GenArgs& a) {
  // gen writes no data on stdout, and its outputs are not held to the end:
  // each case's scene is read back to compute its trace, and the list of the
  // files it will write must be on disk before them (gen_directory.h).
  const CommitsAtOnce at_once;
  const Scenario* scenario = find_scenario(a.scenario);
  if (!scenario) {
    std::string names;
    for (const Scenario& s : scenarios()) names += std::string(names.empty() ? "" : ", ") + s.name;
    throw UsageError(fmt::format("unknown scenario '{}'; scenarios: {}", a.scenario, names));
  }
  if (a.rays <= 0) throw UsageError("option '--rays': must be > 0");
  std::map<std::string, std::string> values;
  std::string generator = fmt::format("vbsim gen {} --rays {} --seed {}", a.scenario, a.rays, a.seed);
  for (const std::string& kv : a.set) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError(fmt::format("option '--set {}': expected key=value", kv));
    values[kv.substr(0, eq)] = kv.substr(eq + 1);
    generator += " --set " + kv;
  }
  const ScenarioSettings settings(a.rays, a.seed, values);
  std::vector<ScenarioCase> cases;
  try {
    cases = scenario->generate(settings);
    settings.check_all_read(a.scenario);
  } catch (const SceneError&) {  // a scene=FILE that cannot be loaded: a runtime error
    throw;
  } catch (const std::runtime_error& e) {  // a bad --set value, an unknown key, settings that cannot work
    throw UsageError(e.what());
  }
  if (a.seed_given && !settings.seed_read() && !a.quiet)
    fmt::print(stderr, "vbsim gen: warning: option '--seed {}' has no effect: {} with these settings is the same "
                       "for every seed{}\n",
               a.seed, a.scenario,
               values.count("protocol") && values.at("protocol") == "pbrt-v4"
                   ? " (protocol=pbrt-v4 takes pbrt-v4's trials RNG(first), RNG(first+1), ...: choose them with "
                     "--set first=N)"
                   : "");
  prepare_gen_directory(a.out_dir);
  std::filesystem::create_directories(a.out_dir);

  // The files every case will write, listed before writing (gen_directory.h).
  std::vector<std::string> planned, inputs;
  uint64_t total = 0;
  for (const ScenarioCase& c : cases) {
    if (c.scene_file.empty()) planned.push_back(c.name + ".ply");
    else inputs.push_back(c.scene_file);
    planned.push_back(c.name + ".jsonl");
    total += c.rays.size();
  }
  write_gen_manifest(a.out_dir, planned, false, provenance_json(inputs));

  ProgressMeter meter("gen: oracle", total, "rays", ProgressMeter::terminal_or_null(a.quiet));
  std::vector<std::string> written;
  CaseWriteOptions options;
  options.written = &written;
  options.on_rays = [&meter](uint64_t n) { meter.add(n); };
  for (const ScenarioCase& c : cases) {
    options.provenance = provenance_line({c.scene_file});
    write_scenario_case(c, a.out_dir, generator, options);
  }
  meter.finish();
  write_gen_manifest(a.out_dir, written, true, provenance_json(inputs));
  if (!a.quiet)
    fmt::print(stderr, "vbsim gen {}: {} case(s), {} rays -> {}\n", a.scenario, cases.size(), total, a.out_dir);
}

}  // namespace

void add_gen_command(CLI::App& app) {
  auto args = std::make_shared<GenArgs>();
  std::string help = "scenario:";
  for (const Scenario& s : scenarios()) help += fmt::format(" {} ({})", s.name, s.summary);
  CLI::App* cmd = app.add_subcommand(
      "gen", "generate a scenario's scene and trace with exact expectations (replaces an earlier gen's files "
             "in the directory; refuses trace files gen did not write)");
  cmd->add_option("scenario", args->scenario, help)->required();
  cmd->add_option("--rays", args->rays, "how many rays (for paths: camera paths)")->capture_default_str();
  cmd->add_option("--seed", args->seed, "random seed")->capture_default_str()->each([args](const std::string&) {
    args->seed_given = true;
  });
  cmd->add_option("--set", args->set, "scenario setting key=value (repeatable)");
  cmd->add_option("-o,--out", args->out_dir, "output directory")->required();
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args] { run_gen(*args); });
}

}  // namespace vbsim::cli
