// Cost of the consistency checks next to the replay they guard (hidden: run
// with `vbsim_tests "[.checks-bench]"`). The bundled trace's 1008 rays are
// repeated 200 times with shifted ids (parents stay 1-7 rays back) and go
// through TraceConsistencyChecker with the scene, then through the functional
// replay with method none; prints ns per ray of each.
#include <catch2/catch.hpp>
#include <fmt/core.h>

#include <chrono>

#include "replay/functional_replayer.h"
#include "replay/replay_run.h"
#include "trace/text_trace_reader.h"
#include "trace/trace_consistency.h"

using namespace vbsim;

TEST_CASE("consistency checks against the functional replay, per ray", "[.checks-bench]") {
  TextTraceReader reader(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  const SceneAndBvh sb = load_trace_scene(reader.header());
  std::vector<TraceRay> base;
  for (TraceRay r; reader.next(r);) base.push_back(r);
  std::vector<TraceRay> rays;
  for (int k = 0; k < 200; ++k)
    for (TraceRay r : base) {
      r.id += k * 1008;
      if (r.parent >= 0) r.parent += k * 1008;
      rays.push_back(r);
    }
  using clock = std::chrono::steady_clock;
  TraceConsistencyChecker::Options opt;
  opt.triangles = &sb.scene.triangles;
  TraceConsistencyChecker checker(opt);
  std::vector<TraceFinding> findings;
  auto t0 = clock::now();
  for (const TraceRay& r : rays) checker.check(r, r.id, "line", findings);
  const double check_s = std::chrono::duration<double>(clock::now() - t0).count();
  CHECK(findings.empty());
  FunctionalReplayer replayer(sb.scene, sb.bvh, ReplayOptions{});
  t0 = clock::now();
  for (const TraceRay& r : rays) replayer.replay(r);
  const double replay_s = std::chrono::duration<double>(clock::now() - t0).count();
  fmt::print("{} rays: checks {:.1f} ns/ray, replay (method none) {:.1f} ns/ray, checks / replay {:.3f}\n", rays.size(),
             1e9 * check_s / rays.size(), 1e9 * replay_s / rays.size(), check_s / replay_s);
}
