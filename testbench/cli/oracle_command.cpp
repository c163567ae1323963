// vbsim oracle: fills in `expect` for every ray of a trace with the exact answer.
#include <fmt/format.h>

#include <chrono>

#include "commands.h"
#include "io/output_paths.h"
#include "exact/expected_answers.h"
#include "progress/progress_meter.h"
#include "provenance/provenance.h"
#include "replay/replay_run.h"
#include "trace/checked_trace_source.h"
#include "trace/trace_file.h"
#include "trace/trace_header_json.h"
#include "trace/trace_ray_count.h"

namespace vbsim::cli {

namespace {

struct OracleArgs {
  std::string trace, out;
  bool quiet = false;
  int64_t parent_window = ParentRayStore::kDefaultWindow;
};

void run_oracle(const OracleArgs& a) {
  auto file = open_trace(a.trace);
  check_output_paths({{"trace", a.trace}, {"scene", file->header().scene_path}}, {{"option '--out'", a.out}});
  const SceneAndBvh sb = load_trace_scene(file->header());
  TraceConsistencyChecker::Options checks;
  checks.triangles = &sb.scene.triangles;
  checks.window = static_cast<std::size_t>(a.parent_window);  // one window for the checks and the oracle
  auto source = std::make_unique<CheckedTraceSource>(*file, checks);  // children after parents, as the oracle needs
  source->set_triangle_count(sb.scene.size());
  TraceHeader header = source->header();
  header.scene = scene_relative_to(header.scene_path, a.out);
  header.provenance = provenance_line({a.trace, header.scene_path});
  auto sink = create_trace_writer(a.out, header);
  ExpectationFiller filler(sb.scene, sb.bvh, a.parent_window);  // parents precede children, as in a replay
  std::FILE* terminal = ProgressMeter::terminal_or_null(a.quiet);
  ProgressMeter meter("oracle", terminal ? count_trace_rays(a.trace) : 0, "rays", terminal);
  TraceRay tr;
  int64_t rays = 0, hits = 0;
  const auto t0 = std::chrono::steady_clock::now();
  while (source->next(tr)) {
    const OracleAnswer ans = replay_at_trace_ray(*source, [&] { return filler.fill(tr); });
    sink->write(tr);
    ++rays;
    hits += ans.prim >= 0;
    if (rays % 256 == 0) meter.update(rays);
  }
  sink->close();
  fmt::print(stderr, "{}", source->warning_lines("vbsim oracle", false));
  meter.finish();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.quiet)
    fmt::print(stderr, "vbsim oracle: {} rays ({} hit), {:.3f} s, {:.0f} rays/s -> {}\n", rays, hits, s,
               s > 0 ? rays / s : 0.0, a.out);
}

}  // namespace

void add_oracle_command(CLI::App& app) {
  auto args = std::make_shared<OracleArgs>();
  CLI::App* cmd = app.add_subcommand("oracle", "fill in the exact answer (expect) of every ray");
  cmd->add_option("trace", args->trace, "input trace")->required();
  cmd->add_option("-o,--out", args->out, "output trace (.jsonl or .vbt)")->required();
  add_parent_window_option(*cmd, args->parent_window);
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args] { run_oracle(*args); });
}

}  // namespace vbsim::cli
