// vbsim explore: a design-space exploration (docs/explore.md). The
// exploration is scripts/explore.py (its points are vbsim processes, run in
// parallel or on Slurm); this command runs it with /usr/bin/python3, passing
// every argument through and naming this program as the one its points run.
// The script is found in $VBSIM_SCRIPTS_DIR, else in the source tree this
// program was built from.
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"

namespace vbsim::cli {

namespace {

std::string explore_script() {
  const char* env = std::getenv("VBSIM_SCRIPTS_DIR");
  const std::string dir = env && *env ? env : std::string(VBSIM_SOURCE_DIR) + "/scripts";
  const std::string script = dir + "/explore.py";
  if (!std::filesystem::exists(script))
    throw std::runtime_error("explore: no " + script + " (set VBSIM_SCRIPTS_DIR to the scripts/ of a vbsim source tree)");
  return script;
}

}  // namespace

void add_explore_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "explore", "design-space exploration: DEFINITION.json -o DIR (points.csv, report.md); --help for its options");
  cmd->set_help_flag();  // --help goes to the script, which knows the options
  cmd->prefix_command();
  cmd->callback([cmd] {
    const std::string script = explore_script();
    std::error_code ec;
    const std::string self = std::filesystem::read_symlink("/proc/self/exe", ec).string();
    if (ec) throw std::runtime_error("explore: cannot find this program's path (/proc/self/exe)");
    std::vector<std::string> args{"/usr/bin/python3", script};
    for (const std::string& a : cmd->remaining()) args.push_back(a);
    args.push_back("--vbsim");
    args.push_back(self);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(stdout);
    ::execv(argv[0], argv.data());
    throw std::runtime_error(std::string("explore: cannot run /usr/bin/python3: ") + std::strerror(errno));
  });
}

}  // namespace vbsim::cli
