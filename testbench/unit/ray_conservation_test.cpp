// Ray conservation: the check itself, and whole replays (functional, cycle
// level, score) counting every ray of the bundled trace exactly once.
#include <catch2/catch.hpp>

#include "hw/cycle_replay.h"
#include "replay/ray_conservation.h"
#include "replay/replay_run.h"
#include "score/score_run.h"
#include "trace/trace_file.h"

using namespace vbsim;

namespace {
const std::string kTrace = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";
}

TEST_CASE("conservation check: rays in must equal rays out plus dropped", "[conservation]") {
  CHECK_NOTHROW(check_ray_conservation("run", 10, 10));
  CHECK_NOTHROW(check_ray_conservation("run", 10, 7, 3));
  CHECK_THROWS_WITH(check_ray_conservation("t.jsonl (tmin)", 10, 9),
                    Catch::StartsWith("t.jsonl (tmin): ray conservation broken: 10 rays read, 9 counted"));
  CHECK_THROWS_AS(check_ray_conservation("run", 10, 11), ConservationError);
  CHECK_THROWS_WITH(check_ray_conservation("run", 10, 5, 2), Catch::Contains("2 dropped in flight"));
}

TEST_CASE("conservation: functional, cycle-level and score runs count every ray once", "[conservation]") {
  auto source = open_trace(kTrace);
  const SceneAndBvh sb = load_trace_scene(source->header());
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method("validity-bit", opt.method, err));
  const ReplayStats functional = run_replay(*source, sb, opt, nullptr);
  CHECK(functional.total().rays == 1008);

  auto again = open_trace(kTrace);
  again->set_triangle_count(sb.scene.size());
  const hw::HwConfig cfg = hw::load_preset("small", "test");
  const hw::CycleRunResult cycle =
      hw::run_cycle_replay([&](TraceRay& tr) { return again->next(tr); }, sb.scene, sb.bvh, opt, cfg, {}, {});
  CHECK(cycle.stats.total().rays == 1008);
  CHECK(cycle.stats.rays_dropped == 0);
  for (int k = 0; k < kRayKindCount; ++k) CHECK(cycle.stats.by_kind[k].rays == functional.by_kind[k].rays);

  ScoreRunOptions two_threads;
  two_threads.threads = 2;
  const std::vector<ScoreCell> cells =
      run_score(collect_score_families({kTrace}), score_configs({MethodSpec{"tmin", opt}}, {TesterKind::ThreeHalfPlane}), two_threads);
  REQUIRE(cells.size() == 1);
  CHECK(cells[0].stats.total().rays == 1008);
}
