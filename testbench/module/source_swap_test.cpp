// The ray source replaced by a module written here (AcceleratorUnits::
// ray_source, RaySourceIf): it reads the feed, emits each ray through the
// replayer in trace order and dispatches one every `interval` cycles, waiting
// for a slot when all are busy. Every ray of the bundled trace finishes with
// the built-in source's hit; the dispatch cycles follow its rule.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <memory>
#include <vector>

#include "hw/cycle_replay.h"
#include "hw/source/ray_source_if.h"
#include "replay/replay_run.h"
#include "trace/trace_source.h"

using namespace vbsim;
using namespace vbsim::hw;

namespace {

/// What a PacedSource saw, owned by the test (the module dies with the accelerator).
struct SourceLog {
  std::vector<uint64_t> dispatched;  ///< dispatch cycle of each ray, in trace order
  uint64_t finished = 0, refused = 0;
};

/// Rays in trace order, one every `interval` cycles, each as soon as a slot is
/// free; no dependencies, no window, no emission time.
class PacedSource final : public sc_core::sc_module, public RaySourceIf {
 public:
  PacedSource(sc_core::sc_module_name n, FunctionalReplayer& replayer, uint32_t interval, SourceLog& log)
      : sc_core::sc_module(n), replayer_(replayer), interval_(interval), log_(log) {}

  void set_feed(RayFeed feed) override { feed_ = std::move(feed); }
  uint32_t event_ids() const override { return 1; }
  void start(SourceHost& host, uint64_t at) override {
    host_ = &host;
    read_next(at);
    if (has_) host_->schedule_source_event(0, at);
  }
  void on_event(uint32_t, uint64_t at) override {
    if (!has_) return;
    if (!host_->try_dispatch(next_, at)) {  // every slot busy: on_slot_free tries again
      ++log_.refused;
      waiting_ = true;
      return;
    }
    log_.dispatched.push_back(at);
    earliest_ = at + interval_;
    read_next(earliest_);
    if (has_) host_->schedule_source_event(0, earliest_);
  }
  void on_finish(uint64_t, uint64_t) override { ++log_.finished; }
  void on_slot_free(uint64_t at) override {
    if (!waiting_) return;
    waiting_ = false;
    host_->schedule_source_event(0, std::max(at, earliest_));
  }
  bool all_done() const override { return ended_ && log_.finished == read_; }
  uint64_t rays_read() const override { return read_; }

 private:
  void read_next(uint64_t at) {
    TraceRay tr;
    has_ = feed_(tr);
    if (!has_) {
      ended_ = true;
      return;
    }
    next_.tr = tr;
    next_.er = replayer_.emit(tr);  // the datapath's emission, in trace order
    next_.index = read_++;
    next_.ready = next_.emitted = next_.entered = at;
  }

  FunctionalReplayer& replayer_;
  uint32_t interval_;
  SourceLog& log_;
  RayFeed feed_;
  SourceHost* host_ = nullptr;
  SourceRay next_;
  bool has_ = false, ended_ = false, waiting_ = false;
  uint64_t read_ = 0, earliest_ = 0;
};

struct Result {
  CycleRunResult run;
  std::map<uint64_t, int32_t> prims;  ///< by trace position
};

Result replay(const HwConfig& cfg, const AcceleratorUnits& units) {
  auto src = open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  const SceneAndBvh sb = load_trace_scene(src->header());
  src->set_triangle_count(sb.scene.size());
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method("validity-bit", opt.method, err));
  Result r;
  CycleRunOptions options;
  options.units = units;
  r.run = run_cycle_replay([&](TraceRay& ray) { return src->next(ray); }, sb.scene, sb.bvh, opt, cfg,
                           [&](const TraceRay&, const RayOutcome& out, uint64_t, uint64_t index) {
                             r.prims[index] = out.hit.prim;
                           },
                           options);
  return r;
}

}  // namespace

TEST_CASE("a ray source of one's own takes the built-in one's place", "[module][swap][source]") {
  HwConfig cfg = load_preset("small", "test");
  cfg.cores = 1;
  cfg.slots_per_core = 4;  // few slots: the source must wait for them
  const Result builtin = replay(cfg, {});
  const uint32_t interval = GENERATE(1u, 7u);
  INFO("interval " << interval);
  SourceLog log;
  AcceleratorUnits units;
  units.ray_source = [&](const char* name, const HwConfig&, FunctionalReplayer& replayer) {
    return std::make_unique<PacedSource>(name, replayer, interval, log);
  };
  const Result paced = replay(cfg, units);
  REQUIRE(paced.prims.size() == builtin.prims.size());
  CHECK(paced.prims == builtin.prims);  // the same hits: the emission is the datapath's
  REQUIRE(log.dispatched.size() == builtin.prims.size());
  CHECK(log.finished == log.dispatched.size());
  CHECK(log.refused > 0);  // 4 slots: it had to wait for one
  // Its rule: the first ray at cycle 0, each next one `interval` or more after.
  CHECK(log.dispatched.front() == 0);
  size_t too_soon = 0;
  for (size_t i = 1; i < log.dispatched.size(); ++i) too_soon += log.dispatched[i] < log.dispatched[i - 1] + interval;
  CHECK(too_soon == 0);
  CHECK(paced.run.hw["source"] == nlohmann::json{{"replaced", true}});
  CHECK(paced.run.hw["emission"] == nlohmann::json{{"replaced", true}});
  CHECK(paced.run.hw["utilisation"]["source"].is_null());
  CHECK(paced.run.counters.rays == builtin.prims.size());
}

namespace {

/// A module that is no ray source.
struct NotASource final : sc_core::sc_module {
  explicit NotASource(sc_core::sc_module_name n) : sc_core::sc_module(n) {}
};

}  // namespace

TEST_CASE("a ray source replacement must implement RaySourceIf", "[module][swap][source]") {
  AcceleratorUnits units;
  units.ray_source = [](const char* name, const HwConfig&, FunctionalReplayer&) {
    return std::make_unique<NotASource>(name);
  };
  CHECK_THROWS_WITH(replay(load_preset("small", "test"), units), Catch::Contains("RaySourceIf"));
}
