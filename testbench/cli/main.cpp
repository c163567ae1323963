// vbsim: command-line entry point. With no arguments it runs the main job (the
// bundled default trace through the validity-bit unit); otherwise a subcommand.
// Exit codes are those of exit_codes.h; status and errors go to stderr, data
// (tables, reports) to stdout.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <systemc>

#include "commands.h"
#include "exit_codes.h"
#include "io/output_paths.h"
#include "provenance/provenance.h"
#include "systemc_messages.h"

int sc_main(int argc, char** argv) {
  using namespace vbsim::cli;
  vbsim::set_command_line(argc, argv);
  route_systemc_messages_to_stderr();
  CLI::App app{
      "vbsim: cycle-level simulator of a ray-tracing accelerator with validity-bit "
      "self-intersection avoidance"};
  app.set_version_flag("--version", vbsim::vbsim_version_line(), "print the version and git revision");
  app.footer("Exit codes: 0 success, 1 runtime error, 2 usage error, 130 interrupted.");
  app.require_subcommand(0, 1);
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
  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) return run_default_job();
  } catch (const CLI::RuntimeError& e) {  // a command's own exit code (e.g. 130)
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every real parse error is a usage error.
    const int printed = app.exit(e);
    return printed == 0 ? kExitSuccess : kExitUsage;
  } catch (const UsageError& e) {
    fmt::print(stderr, "vbsim: usage error: {}\nRun with --help for more information.\n", e.what());
    return kExitUsage;
  } catch (const vbsim::OutputPathError& e) {  // an output naming an input: refused before any work
    fmt::print(stderr, "vbsim: usage error: {}\n", e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    fmt::print(stderr, "vbsim: error: {}\n", e.what());
    return kExitRuntimeError;
  }
  return kExitSuccess;
}

// libsystemc.so brings a main() that calls sc_main(); this one (which the
// linker prefers) only silences SystemC's banner first.
int main(int argc, char** argv) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  return sc_core::sc_elab_and_sim(argc, argv);
}
