// vbsim scenarios: the registered scenarios of `vbsim gen`, one per line
// ("NAME<TAB>summary"), so that scripts pick up scenarios added later.
#include <fmt/format.h>

#include "commands.h"
#include "gen/scenario.h"

namespace vbsim::cli {

void add_scenarios_command(CLI::App& app) {
  auto names_only = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("scenarios", "list the scenarios of vbsim gen");
  cmd->add_flag("--names", *names_only, "print the names only");
  cmd->callback([names_only] {
    for (const Scenario& s : scenarios()) {
      if (*names_only) fmt::print("{}\n", s.name);
      else fmt::print("{}\t{}\n", s.name, s.summary);
    }
  });
}

}  // namespace vbsim::cli
