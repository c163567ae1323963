// vbsim: command-line entry point. With no arguments it runs the main job (the
// bundled default trace through the validity-bit unit); otherwise a subcommand.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <systemc>

#include "commands.h"

int sc_main(int argc, char** argv) {
  using namespace vbsim::cli;
  CLI::App app{
      "vbsim: cycle-level simulator of a ray-tracing accelerator with validity-bit "
      "self-intersection avoidance"};
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
  add_reintersect_command(app);
  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) return run_default_job();
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    fmt::print(stderr, "vbsim: error: {}\n", e.what());
    return 2;
  }
  return 0;
}

// libsystemc.so brings a main() that calls sc_main(); this one (which the
// linker prefers) only silences SystemC's banner first.
int main(int argc, char** argv) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  return sc_core::sc_elab_and_sim(argc, argv);
}
