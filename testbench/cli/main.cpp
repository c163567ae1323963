// vbsim: command-line entry point. With no arguments it runs the main job (the
// bundled default trace through the validity-bit unit); otherwise a subcommand.
// Exit codes are those of exit_codes.h; status and errors go to stderr, data
// (tables, reports) to stdout.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>
#include <system_error>
#include <vector>
#include <systemc>

#include "commands.h"
#include "exit_codes.h"
#include "numeric_options.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"
#include "provenance/provenance.h"
#include "standard_streams.h"
#include "systemc_messages.h"

namespace {

/// An option or argument given as an empty string names nothing: an empty
/// output path would otherwise be skipped silently, an empty input fail with
/// a raw file-system message.
void refuse_empty_values(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands())
    for (const CLI::Option* opt : sub->get_options())
      for (const std::string& value : opt->results())
        if (value.empty())
          throw vbsim::cli::UsageError(opt->get_positional()
                                           ? fmt::format("argument '{}': empty value", opt->get_name(true))
                                           : fmt::format("option '{}': empty value", opt->get_name()));
}

int run_command_line(int argc, char** argv) {
  using namespace vbsim::cli;
  route_systemc_messages_to_stderr();
  CLI::App app{
      "vbsim: cycle-level simulator of a ray-tracing accelerator with validity-bit "
      "self-intersection avoidance"};
  app.set_version_flag("--version", vbsim::vbsim_version_line(), "print the version and git revision");
  app.footer("Exit codes: 0 success, 1 runtime error, 2 usage error, 130 interrupted.");
  app.require_subcommand(0, 1);
  app.parse_complete_callback([&app] {
    refuse_empty_values(app);
    check_numeric_option_values(app);  // no wrapped, cut or octal numbers (numeric_options.h)
  });
  add_replay_command(app);
  add_convert_command(app);
  add_bench_command(app);
  add_oracle_command(app);
  add_gen_command(app);
  add_watertight_command(app);
  add_score_command(app);
  add_scenarios_command(app);
  add_fit_command(app);
  add_render_command(app);
  add_hw_command(app);
  add_check_command(app);
  add_capture_command(app);
  add_reintersect_command(app);
  add_compare_reference_command(app);
  add_explore_command(app);
  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) return run_default_job();
  } catch (const CLI::RuntimeError& e) {  // a command's own exit code (e.g. 130)
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0, also when their reader has gone (`| head`);
    // every real parse error is a usage error.
    const int printed = app.exit(e);
    if (printed == 0) ignore_standard_output_errors();
    return printed == 0 ? kExitSuccess : kExitUsage;
  } catch (const UsageError& e) {
    fmt::print(stderr, "vbsim: usage error: {}\nRun with --help for more information.\n", e.what());
    return kExitUsage;
  } catch (const vbsim::OutputPathError& e) {  // an output naming an input: refused before any work
    fmt::print(stderr, "vbsim: usage error: {}\n", e.what());
    return kExitUsage;
  } catch (const std::bad_alloc&) {  // says nothing of its own: name the run and the inputs it was given
    fmt::print(stderr, "vbsim: error: out of memory running '{}' (the inputs or settings above need more memory "
                       "than this machine gives; docs/reliability.md, \"Bounded memory\")\n",
               fmt::join(std::vector<std::string>(argv, argv + argc), " "));
    return kExitRuntimeError;
  } catch (const std::system_error& e) {
    // fmt's "cannot write to file" when data on stdout did not arrive: said
    // once, by sc_main, as standard output's error with its reason.
    if (std::ferror(stdout)) return kExitRuntimeError;
    fmt::print(stderr, "vbsim: error: {}\n", e.what());
    return kExitRuntimeError;
  } catch (const std::exception& e) {
    fmt::print(stderr, "vbsim: error: {}\n", e.what());
    return kExitRuntimeError;
  }
  return kExitSuccess;
}

}  // namespace

int sc_main(int argc, char** argv) {
  using namespace vbsim::cli;
  guard_standard_streams();
  vbsim::exit_on_interrupt(kExitInterrupted);  // commands that stop cleanly install their own handler
  vbsim::set_command_line(argc, argv);
  // Data on stdout is an output like any other: the files a run writes are
  // renamed to their names only once its data on stdout has arrived, and one
  // that did not arrive fails the run and leaves none of them.
  vbsim::hold_output_commits();
  const int code = run_command_line(argc, argv);
  const std::string stdout_error = standard_output_error();
  if (!stdout_error.empty()) {
    vbsim::discard_held_outputs();
    fmt::print(stderr, "vbsim: error: standard output: {}\n", stdout_error);
    return code == kExitSuccess ? kExitRuntimeError : code;
  }
  try {
    vbsim::commit_held_outputs();
  } catch (const vbsim::OutputError& e) {
    fmt::print(stderr, "vbsim: error: {}\n", e.what());
    return code == kExitSuccess ? kExitRuntimeError : code;
  }
  return code;
}

// libsystemc.so brings a main() that calls sc_main(); this one (which the
// linker prefers) only silences SystemC's banner first.
int main(int argc, char** argv) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  return sc_core::sc_elab_and_sim(argc, argv);
}
