// The vbsim subcommands. Each add_*_command registers its options on the app and
// sets a callback; errors are thrown and reported once by main().
#pragma once
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace vbsim::cli {

/// The bundled default trace (used by `vbsim` with no arguments).
std::string default_trace_path();

void add_replay_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_oracle_command(CLI::App& app);
void add_gen_command(CLI::App& app);
void add_watertight_command(CLI::App& app);
void add_score_command(CLI::App& app);
void add_scenarios_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_hw_command(CLI::App& app);
void add_check_command(CLI::App& app);
void add_capture_command(CLI::App& app);
void add_reintersect_command(CLI::App& app);
void add_compare_reference_command(CLI::App& app);
void add_explore_command(CLI::App& app);

/// The main job: replay of the default trace with validity-bit, printed
/// summary, then the trade-off table of every method on the same trace.
int run_default_job();
/// Prints the trade-off table of every default score method on `trace`.
void print_tradeoff_table(const std::string& trace);

/// `--parent-window N`: rays kept for children to find their parent in
/// (ParentRayStore; the consistency checks look as far back), checked to be
/// in 1..ParentRayStore::kMaxWindow. `names` as CLI11 takes them.
void add_parent_window_option(CLI::App& cmd, int64_t& window, const std::string& names = "--parent-window");

}  // namespace vbsim::cli
