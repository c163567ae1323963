// vbsim's exit codes, the same for every command (README "Exit codes"):
//   0   success
//   1   runtime error: bad input file, unreadable or unwritable file, a failed check
//   2   usage error: unknown command or option, a missing or malformed argument,
//       an option value out of range (CLI11's parse errors map here too)
//   130 interrupted (SIGINT or SIGTERM): a replay stops, writes its statistics
//       marked partial and exits 130; other commands remove their unfinished
//       outputs and exit 130 (io/atomic_output_file.h, exit_on_interrupt)
// Commands throw UsageError for a bad command line and any other exception
// for a runtime error; main() reports it once on stderr and picks the code.
#pragma once
#include <stdexcept>

namespace vbsim::cli {

constexpr int kExitSuccess = 0;
constexpr int kExitRuntimeError = 1;
constexpr int kExitUsage = 2;
constexpr int kExitInterrupted = 130;

/// A command line that cannot run: reported as "vbsim: usage error: ...", exit 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace vbsim::cli
