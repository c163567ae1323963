// --threads N: the worker threads of a command whose outputs do not depend on
// their number (replay's functional mode, oracle, check, score): every core by
// default. The recorded command line leaves the option out, so that outputs
// are byte-identical, provenance included, whatever it is set to.
#pragma once
#include <CLI/CLI.hpp>
#include <string>

namespace vbsim::cli {

/// The host's cores (at least 1): the default of --threads.
int all_cores();

/// Adds --threads to `cmd`; `what` says what runs on the threads.
CLI::Option* add_threads_option(CLI::App& cmd, int& threads, const std::string& what);

/// Throws UsageError unless `threads` >= 1; drops --threads from the recorded
/// command line (provenance).
void check_threads_option(int threads);

}  // namespace vbsim::cli
