// vbsim gen: writes a scenario's scenes and traces, with `expect` filled in by
// the exact oracle (model/gen/scenario.h).
#include <fmt/format.h>

#include <map>

#include "commands.h"
#include "gen/scenario.h"

namespace vbsim::cli {

namespace {

struct GenArgs {
  std::string scenario;
  int64_t rays = 200;
  uint64_t seed = 1;
  std::vector<std::string> set;
  std::string out_dir;
};

void run_gen(const GenArgs& a) {
  const Scenario* scenario = find_scenario(a.scenario);
  if (!scenario) {
    std::string names;
    for (const Scenario& s : scenarios()) names += std::string(names.empty() ? "" : ", ") + s.name;
    throw std::runtime_error(fmt::format("unknown scenario '{}'; scenarios: {}", a.scenario, names));
  }
  std::map<std::string, std::string> values;
  std::string generator = fmt::format("vbsim gen {} --rays {} --seed {}", a.scenario, a.rays, a.seed);
  for (const std::string& kv : a.set) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw std::runtime_error(fmt::format("option '--set {}': expected key=value", kv));
    values[kv.substr(0, eq)] = kv.substr(eq + 1);
    generator += " --set " + kv;
  }
  const ScenarioSettings settings(a.rays, a.seed, values);
  const std::vector<ScenarioCase> cases = scenario->generate(settings);
  settings.check_all_read(a.scenario);
  size_t rays = 0;
  for (const ScenarioCase& c : cases) {
    write_scenario_case(c, a.out_dir, generator);
    rays += c.rays.size();
  }
  fmt::print("vbsim gen {}: {} case(s), {} rays -> {}\n", a.scenario, cases.size(), rays, a.out_dir);
}

}  // namespace

void add_gen_command(CLI::App& app) {
  auto args = std::make_shared<GenArgs>();
  std::string help = "scenario:";
  for (const Scenario& s : scenarios()) help += fmt::format(" {} ({})", s.name, s.summary);
  CLI::App* cmd = app.add_subcommand("gen", "generate a scenario's scene and trace with exact expectations");
  cmd->add_option("scenario", args->scenario, help)->required();
  cmd->add_option("--rays", args->rays, "how many rays (for paths: camera paths)")->capture_default_str();
  cmd->add_option("--seed", args->seed, "random seed")->capture_default_str();
  cmd->add_option("--set", args->set, "scenario setting key=value (repeatable)");
  cmd->add_option("-o,--out", args->out_dir, "output directory")->required();
  cmd->callback([args] { run_gen(*args); });
}

}  // namespace vbsim::cli
