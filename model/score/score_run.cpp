#include "score/score_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <set>

#include "replay/functional_replayer.h"
#include "replay/ray_conservation.h"
#include "replay/replay_run.h"
#include "score/cycle_cost.h"
#include "parallel/parallel_for.h"
#include "trace/trace_blocks.h"
#include "trace/checked_trace_source.h"
#include "trace/trace_file.h"

namespace vbsim {

namespace fs = std::filesystem;

namespace {

/// Rays parsed at a time; every configuration replays a block before the next is read.
constexpr size_t kBlockRays = 16384;

bool is_trace_file(const fs::path& p) {
  const std::string ext = p.extension().string();
  return fs::is_regular_file(p) && (ext == ".jsonl" || ext == ".vbt");
}

bool same_verdicts(const ReplayStats& a, const ReplayStats& b) {
  for (int k = 0; k < kRayKindCount; ++k)
    if (a.by_kind[k].rays != b.by_kind[k].rays || a.by_kind[k].verdicts != b.by_kind[k].verdicts) return false;
  return true;
}

bool measures_cycles(const ScoreRunOptions& run, const ScoreConfig& c) {
  // The renderer's own answers come from no search of the modelled hardware: nothing to time.
  return run.cycle && !c.options.reference_answers && std::find(run.cycle_testers.begin(), run.cycle_testers.end(), c.options.tester) !=
                          run.cycle_testers.end();
}

/// The cycle-level cost of configuration `c` on the trace at `path`, read a
/// second time and streamed into the model, so that a score run in cycle mode
/// holds no more of the trace than a functional one. The functional pass has
/// read the same file already, so this pass sees the same rays.
CycleCost trace_cycle_cost(const std::string& path, const SceneAndBvh& sb, const ScoreConfig& c,
                           const ScoreRunOptions& run) {
  auto source = open_trace(path);
  source->set_triangle_count(sb.scene.size());
  ReplayOptions opt = c.options;
  opt.parent_window = run.parent_window;
  const hw::RayFeed feed = [&](TraceRay& tr) { return source->next(tr); };
  const hw::RayLocator locate = [&](const std::string& field, const std::string& message) {
    return std::string(source->error_at_last_ray(field, message).what());
  };
  return cycle_replay_cost(feed, sb.scene, sb.bvh, opt, run.hw, locate, run.tech);
}

/// Replays one trace with every configuration, adding into cells[0..configs),
/// in blocks of kBlockRays. Cycle mode then replays the trace through the
/// cycle-level model for every timed configuration, one after the other.
void score_trace(const std::string& path, const std::vector<ScoreConfig>& configs,
                 std::vector<CandidateFilter>& filters, ScoreCell* cells, const ScoreRunOptions& run) {
  auto file = open_trace(path);
  // The consistency checks every reader applies: a child after its parent (an error naming the line).
  TraceConsistencyChecker::Options checks;
  checks.window = static_cast<std::size_t>(run.parent_window);  // the window the replays keep parents in
  CheckedTraceSource source(*file, checks);
  const SceneAndBvh sb = load_trace_scene(source.header());
  check_traversal_depth(sb.bvh);
  source.set_triangle_count(sb.scene.size());
  TraceBlocks blocks(source, run.parent_window);
  std::vector<ReplayStats> stats(configs.size());
  while (blocks.next_block(kBlockRays)) {
    parallel_for(configs.size(), run.threads, [&](size_t c) {
      const auto start = std::chrono::steady_clock::now();
      const std::vector<TraceRay>& rays = blocks.rays();
      for (size_t i = 0; i < rays.size(); ++i) {
        KindStats& ks = stats[c].by_kind[static_cast<int>(rays[i].kind)];
        replay_one_ray(rays[i], sb.scene, sb.bvh, configs[c].options, filters[c], blocks.parents_for(i), ks);
      }
      stats[c].wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    });
    // Cycle mode reports a trace once its cycle-level replays are done too.
    if (run.progress && !run.cycle) run.progress(blocks.rays().size());
  }
  for (size_t c = 0; c < configs.size(); ++c)
    check_ray_conservation(fmt::format("{} ({} {})", path, configs[c].method, tester_name(configs[c].options.tester)),
                           static_cast<uint64_t>(blocks.rays_read()), stats[c].total().rays);
  for (size_t c = 0; c < configs.size() && run.cycle; ++c) {
    if (!measures_cycles(run, configs[c])) continue;
    const CycleCost cost = trace_cycle_cost(path, sb, configs[c], run);
    if (!same_verdicts(cost.stats, stats[c]))
      throw std::runtime_error(fmt::format("{}: the cycle-level replay of '{}' with the {} tester gave other "
                                           "verdicts than the functional replay",
                                           path, configs[c].method, tester_name(configs[c].options.tester)));
    cells[c].has_cycles = true;
    cells[c].cycle_preset = run.hw.preset;
    cells[c].cycle_rays += cost.rays;
    cells[c].cycles += cost.cycles;
    cells[c].cycle_total_pj += cost.total_pj;
    cells[c].chip_mm2 = cost.chip_mm2;
  }
  if (run.progress && run.cycle) run.progress(static_cast<uint64_t>(blocks.rays_read()));
  for (size_t c = 0; c < configs.size(); ++c) {
    for (int k = 0; k < kRayKindCount; ++k) cells[c].stats.by_kind[k].add(stats[c].by_kind[k]);
    cells[c].stats.wall_s += stats[c].wall_s;
    ++cells[c].traces;
  }
}

}  // namespace

std::vector<ScoreFamily> collect_score_families(const std::vector<std::string>& paths) {
  std::vector<ScoreFamily> out;
  std::set<std::string> names;
  for (const std::string& p : paths) {
    const fs::path path(p);
    ScoreFamily fam;
    if (fs::is_directory(path)) {
      fam.name = fs::absolute(path).lexically_normal().parent_path().filename().string();
      if (path.filename() != "" && path.filename() != ".") fam.name = path.filename().string();
      for (const auto& e : fs::directory_iterator(path))
        if (is_trace_file(e.path())) fam.traces.push_back(e.path().string());
      std::sort(fam.traces.begin(), fam.traces.end());
      if (fam.traces.empty()) throw std::runtime_error(fmt::format("{}: no trace files (.jsonl, .vbt) in this directory", p));
    } else if (fs::is_regular_file(path)) {
      fam.name = path.stem().string();
      fam.traces.push_back(p);
    } else if (fs::exists(path)) {
      throw std::runtime_error(fmt::format("{}: not a regular file (a pipe or a device): score and fit read a trace "
                                           "more than once (its header, its rays, and in cycle mode a second pass); "
                                           "write it to a file first",
                                           p));
    } else {
      throw std::runtime_error(fmt::format("{}: no such trace file or directory", p));
    }
    fam.generator = open_trace(fam.traces.front())->header().generator;
    if (!names.insert(fam.name).second)
      throw std::runtime_error(fmt::format("{}: a second scenario family named '{}'", p, fam.name));
    out.push_back(std::move(fam));
  }
  return out;
}

std::vector<ScoreConfig> score_configs(const std::vector<MethodSpec>& methods,
                                       const std::vector<TesterKind>& testers) {
  std::vector<ScoreConfig> out;
  for (const MethodSpec& m : methods)
    for (TesterKind t : testers) {
      ScoreConfig c{m.label, m.options};
      c.options.tester = t;
      out.push_back(std::move(c));
    }
  return out;
}

std::vector<ScoreCell> run_score(const std::vector<ScoreFamily>& families,
                                 const std::vector<ScoreConfig>& configs, const ScoreRunOptions& options) {
  if (options.threads < 1) throw std::invalid_argument("run_score: threads must be >= 1");
  std::vector<CandidateFilter> filters;
  for (const ScoreConfig& c : configs) filters.emplace_back(c.options.method);
  std::vector<ScoreCell> cells;
  for (const ScoreFamily& fam : families) {
    const size_t first = cells.size();
    for (const ScoreConfig& c : configs) {
      ScoreCell cell;
      cell.family = fam.name;
      cell.method = c.method;
      cell.tester = c.options.tester;
      cell.config = replay_config_json(c.options);
      cell.options = c.options;
      cells.push_back(std::move(cell));
    }
    for (const std::string& trace : fam.traces) score_trace(trace, configs, filters, &cells[first], options);
  }
  return cells;
}

}  // namespace vbsim
