// vbsim watertight: lost rays and double hits per tester on rays aimed exactly
// at shared edges and vertices of closed meshes (see docs/testers.md).
#include <fmt/format.h>

#include "commands.h"
#include "datapath/watertightness.h"

namespace vbsim::cli {

void add_watertight_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "watertight", "measure each tester's lost rays and double hits at shared edges and vertices");
  cmd->callback([] { fmt::print("{}", watertightness_report()); });
}

}  // namespace vbsim::cli
