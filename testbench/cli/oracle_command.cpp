// vbsim oracle: fills in `expect` for every ray of a trace with the exact answer.
#include <fmt/format.h>

#include <chrono>

#include "commands.h"
#include "progress/work_progress.h"
#include "io/output_paths.h"
#include "exact/expectation_block.h"
#include "exact/expected_answers.h"
#include "progress/progress_meter.h"
#include "provenance/provenance.h"
#include "replay/replay_run.h"
#include "threads_option.h"
#include "trace/checked_trace_source.h"
#include "trace/trace_blocks.h"
#include "trace/trace_file.h"
#include "trace/trace_header_json.h"
#include "trace/trace_ray_count.h"

namespace vbsim::cli {

namespace {

struct OracleArgs {
  std::string trace, out;
  bool quiet = false;
  int64_t parent_window = ParentRayStore::kDefaultWindow;
  int threads = 1;  // --threads (every core by default)
};

/// Rays read, answered and written at a time on several threads.
constexpr size_t kBlockRays = 4096;

/// The oracle on `threads` > 1 threads, a block of rays at a time: the same
/// rays written, and the same errors in the same order, as one ray at a time.
void fill_in_blocks(CheckedTraceSource& source, const SceneAndBvh& sb, int64_t parent_window, int threads,
                    TraceSink& sink, ProgressMeter& meter, int64_t& rays, int64_t& hits) {
  source.set_parse_threads(threads);
  const Oracle oracle(sb.scene, sb.bvh);
  TraceBlocks blocks(source, parent_window);
  std::vector<TraceRay> filled;
  for (bool more = true; more;) {
    std::exception_ptr error;  // an error at a ray comes after the rays before it
    try {
      more = blocks.next_block(kBlockRays);
    } catch (...) {
      error = std::current_exception();
    }
    hits += fill_expect_block(oracle, sb.scene, blocks, threads, filled);
    for (const TraceRay& tr : filled) sink.write(tr);
    rays += static_cast<int64_t>(filled.size());
    if (error) std::rethrow_exception(error);
    meter.update(rays);
  }
}

void run_oracle(const OracleArgs& a) {
  check_threads_option(a.threads);
  auto file = open_trace(a.trace);
  check_output_paths({{"trace", a.trace}, {"scene", file->header().scene_path}}, {{"option '--out'", a.out}});
  MeterWorkProgress loading("scene", ProgressMeter::terminal_or_null(a.quiet));
  const SceneAndBvh sb = load_trace_scene(file->header(), {}, &loading);
  loading.finish();
  TraceConsistencyChecker::Options checks;
  checks.triangles = &sb.scene.triangles;
  checks.window = static_cast<std::size_t>(a.parent_window);  // one window for the checks and the oracle
  auto source = std::make_unique<CheckedTraceSource>(*file, checks);  // children after parents, as the oracle needs
  source->set_triangle_count(sb.scene.size());
  TraceHeader header = source->header();
  header.scene = scene_relative_to(header.scene_path, a.out);
  header.provenance = provenance_line({a.trace, header.scene_path});
  auto sink = create_trace_writer(a.out, header);
  std::FILE* terminal = ProgressMeter::terminal_or_null(a.quiet);
  ProgressMeter meter("oracle", terminal ? count_trace_rays(a.trace) : 0, "rays", terminal);
  int64_t rays = 0, hits = 0;
  const auto t0 = std::chrono::steady_clock::now();
  if (a.threads > 1) {
    fill_in_blocks(*source, sb, a.parent_window, a.threads, *sink, meter, rays, hits);
  } else {
    ExpectationFiller filler(sb.scene, sb.bvh, a.parent_window);  // parents precede children, as in a replay
    TraceRay tr;
    while (source->next(tr)) {
      const OracleAnswer ans = replay_at_trace_ray(*source, [&] { return filler.fill(tr); });
      sink->write(tr);
      ++rays;
      hits += ans.prim >= 0;
      if (rays % 256 == 0) meter.update(rays);
    }
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
  add_threads_option(*cmd, args->threads, "threads that parse the rays and compute their exact answers");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args] { run_oracle(*args); });
}

}  // namespace vbsim::cli
