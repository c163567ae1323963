// Cycle-level replay gives the functional replay's answer on every ray of every
// committed trace, for several methods, dispatch policies and stack depths
// (a shallow on-chip stack spills and refills: counted, same hits).
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <map>
#include <vector>

#include "hw/cycle_replay.h"
#include "replay/replay_run.h"
#include "trace/trace_file.h"
#include "trace/trace_source.h"

using namespace vbsim;

namespace {

std::vector<std::string> committed_traces() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(std::string(VBSIM_SOURCE_DIR) + "/traces"))
    if (e.path().extension() == ".jsonl") out.push_back(e.path().string());
  return out;
}

struct Answer {
  int32_t prim;
  float t;
  Verdict verdict;
  uint64_t rejected;
};

bool same(const Answer& a, const Answer& b) {
  return a.prim == b.prim && std::memcmp(&a.t, &b.t, sizeof a.t) == 0 && a.verdict == b.verdict &&
         a.rejected == b.rejected;
}

}  // namespace

TEST_CASE("cycle-level hits equal functional hits on every committed trace", "[cycle][system]") {
  const std::vector<std::string> traces = committed_traces();
  REQUIRE(!traces.empty());
  const std::string method =
      GENERATE(as<std::string>{}, "validity-bit", "none", "primid", "tmin", "offset-adaptive+primid");
  const uint32_t stack_depth = GENERATE(2u, 16u);
  const hw::DispatchPolicy dispatch = GENERATE(hw::DispatchPolicy::RoundRobin, hw::DispatchPolicy::LeastLoaded);
  for (const std::string& path : traces) {
    INFO(path << " method " << method);
    ReplayOptions opt;
    std::string err;
    REQUIRE(parse_method(method, opt.method, err));
    auto functional_src = open_trace(path);
    const SceneAndBvh sb = load_trace_scene(functional_src->header());
    functional_src->set_triangle_count(sb.scene.size());
    std::map<int64_t, Answer> want;
    FunctionalReplayer replayer(sb.scene, sb.bvh, opt);
    TraceRay tr;
    while (functional_src->next(tr)) {
      const RayOutcome out = replayer.replay(tr);
      want[tr.id] = {out.hit.prim, out.hit.t, out.verdict, out.rejected};
    }
    const KindStats want_total = replayer.stats().total();

    hw::HwConfig cfg;
    cfg.cores = 3;
    cfg.slots_per_core = 5;
    cfg.stack_depth = stack_depth;
    cfg.dispatch = dispatch;
    cfg.memory.ideal = true;
    cfg.memory.ideal_latency = 7;
    auto src = open_trace(path);
    src->set_triangle_count(sb.scene.size());
    std::map<int64_t, Answer> got;
    const hw::RayResultSink sink = [&](const TraceRay& r, const RayOutcome& out, uint64_t, uint64_t) {
      got[r.id] = {out.hit.prim, out.hit.t, out.verdict, out.rejected};
    };
    const hw::CycleRunResult run = hw::run_cycle_replay([&](TraceRay& r) { return src->next(r); }, sb.scene, sb.bvh,
                                                        opt, cfg, sink, hw::CycleRunOptions{});
    REQUIRE(got.size() == want.size());
    size_t differ = 0;
    for (const auto& [id, a] : want) differ += !same(a, got.at(id));
    CHECK(differ == 0);
    const KindStats t = run.stats.total();
    CHECK(t.verdicts == want_total.verdicts);
    CHECK(t.candidates.rejected == want_total.candidates.rejected);
    CHECK(t.traversal.node_visits == want_total.traversal.node_visits);
    CHECK(run.stats.mode == "cycle");
    if (cfg.stack_depth == 2) {  // deeper BVHs than 2 levels of pending subtrees: overflow happened
      CHECK(run.counters.spills > 0);
      CHECK(run.counters.refill_reads > 0);
      CHECK(run.hw["stalls"]["stack_overflow"]["spills"].get<uint64_t>() == run.counters.spills);
    }
  }
}
