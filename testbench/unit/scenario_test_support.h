// Test support for the scenarios: generate one in-process into a scratch
// directory (as `vbsim gen` does), replay every case's trace with a method (as
// `vbsim replay` does: scene and transform from the trace header) and sum the
// verdicts, per ray kind.
#pragma once
#include <catch2/catch.hpp>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "gen/scenario.h"
#include "replay/replay_run.h"
#include "trace/trace_file.h"

namespace vbsim::test {

/// Writes scenario `name` with `settings` into a fresh scratch directory (of
/// this process) and
/// returns the cases (with the rays as generated) and their trace paths.
struct GeneratedScenario {
  std::vector<ScenarioCase> cases;
  std::vector<std::string> traces;
};

inline GeneratedScenario generate_scenario(const std::string& name, int64_t rays, uint64_t seed,
                                           const std::map<std::string, std::string>& settings) {
  const Scenario* scenario = find_scenario(name);
  REQUIRE(scenario != nullptr);
  const ScenarioSettings s(rays, seed, settings);
  GeneratedScenario g;
  g.cases = scenario->generate(s);
  s.check_all_read(name);
  // One directory per process: ctest runs test cases in parallel processes.
  const auto dir = std::filesystem::temp_directory_path() /
                   ("vbsim_scenario_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  for (const ScenarioCase& c : g.cases) g.traces.push_back(write_scenario_case(c, dir.string(), "test"));
  return g;
}

/// Verdict counts of one ray kind (or of all rays) over every trace.
struct VerdictCounts {
  uint64_t rays = 0, correct = 0, self_hit = 0, false_hit = 0, missed = 0, unscored = 0;
};

inline VerdictCounts counts_of(const KindStats& k) {
  VerdictCounts c;
  c.rays = k.rays;
  c.correct = k.verdicts[static_cast<int>(Verdict::Correct)];
  c.self_hit = k.verdicts[static_cast<int>(Verdict::SelfHit)];
  c.false_hit = k.verdicts[static_cast<int>(Verdict::FalseHit)];
  c.missed = k.verdicts[static_cast<int>(Verdict::Missed)];
  c.unscored = k.verdicts[static_cast<int>(Verdict::Unscored)];
  return c;
}

/// Replays every trace under `method` (parameters at their defaults, adjusted by
/// `tune`) and returns the summed statistics.
inline ReplayStats replay_traces(const std::vector<std::string>& traces, const std::string& method,
                                 void (*tune)(ReplayOptions&) = nullptr) {
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method(method, opt.method, err));
  if (tune) tune(opt);
  ReplayStats sum;
  for (const std::string& path : traces) {
    auto source = open_trace(path);
    const SceneAndBvh sb = load_trace_scene(source->header());
    const ReplayStats s = run_replay(*source, sb, opt, nullptr);
    for (int k = 0; k < kRayKindCount; ++k) sum.by_kind[k].add(s.by_kind[k]);
  }
  return sum;
}

/// Replays one trace under `method` ray by ray, calling
/// visit(const TraceRay&, const RayOutcome&, const Scene&) for each ray.
template <class Visit>
void visit_outcomes(const std::string& trace, const std::string& method, Visit visit) {
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method(method, opt.method, err));
  auto source = open_trace(trace);
  const SceneAndBvh sb = load_trace_scene(source->header());
  source->set_triangle_count(sb.scene.size());
  FunctionalReplayer replayer(sb.scene, sb.bvh, opt);
  TraceRay tr;
  while (source->next(tr)) visit(tr, replayer.replay(tr), sb.scene);
}

inline VerdictCounts kind_counts(const ReplayStats& s, RayKind kind) {
  return counts_of(s.by_kind[static_cast<int>(kind)]);
}
inline VerdictCounts total_counts(const ReplayStats& s) { return counts_of(s.total()); }

}  // namespace vbsim::test
