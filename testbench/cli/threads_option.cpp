#include "threads_option.h"

#include <algorithm>
#include <thread>

#include "exit_codes.h"
#include "provenance/provenance.h"

namespace vbsim::cli {

int all_cores() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

CLI::Option* add_threads_option(CLI::App& cmd, int& threads, const std::string& what) {
  threads = all_cores();
  return cmd.add_option("--threads", threads, what + "; the outputs are the same for any number [every core]");
}

void check_threads_option(int threads) {
  if (threads < 1) throw UsageError("option '--threads': must be >= 1");
  omit_from_command_line("--threads");
}

}  // namespace vbsim::cli
