// Replacing the memory levels. A replacement L1 that implements L2ClientIf
// reaches the shared L2: the accelerator binds its port to the L2, the L2
// answers its pending lines to it, and the core takes its pending reads'
// answers. Here an L1 without a cache sends every line a read spans to the
// L2: the L2 sees exactly its requests, and the rays' hits stay the
// functional replay's. A replacement L2 takes every built-in L1's misses.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <memory>
#include <vector>

#include "hw/cycle_replay.h"
#include "hw/memory/l2_cache.h"
#include "replay/replay_run.h"
#include "trace/trace_source.h"

using namespace vbsim;
using namespace vbsim::hw;

namespace {

/// What a ForwardingL1 counted, owned by the test (the module dies with the
/// accelerator, before the test reads the counts).
struct Tally {
  uint64_t requests = 0, pending_lines = 0;
};

/// No cache: every line of a read goes to the L2 `latency` cycles after the
/// read; the read's data are there when its last line is.
class ForwardingL1 final : public sc_core::sc_module, public MemoryReadIf, public LineFillIf, public L2ClientIf {
 public:
  sc_core::sc_port<LineReadIf> next;
  sc_core::sc_port<ReadDoneIf> done;

  ForwardingL1(sc_core::sc_module_name n, uint32_t core, uint32_t line_bytes, uint32_t latency, Tally& tally)
      : sc_core::sc_module(n), next("next"), done("done"), tally_(tally), core_(core), line_bytes_(line_bytes),
        latency_(latency) {}

  sc_core::sc_port_b<LineReadIf>& next_level() override { return next; }
  LineFillIf& fill_target() override { return *this; }
  sc_core::sc_port_b<ReadDoneIf>& read_done() override { return done; }

  uint64_t read(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot) override {
    uint64_t ready = now + 1;
    Wait w{0, now + 1};
    for (uint64_t line = addr / line_bytes_; line <= (addr + bytes - 1) / line_bytes_; ++line) {
      ++tally_.requests;
      const uint64_t r = next->read_line(line, now + latency_, core_);
      if (r == kPendingCycle) {
        ++w.lines;
        ++tally_.pending_lines;
        waiting_[line].push_back(slot);
      } else {
        ready = std::max(ready, r);
      }
    }
    if (w.lines == 0) return ready;
    w.ready = ready;
    waits_[slot] = w;
    return kPendingCycle;
  }

  void line_filled(uint64_t line, uint64_t fill) override {
    auto it = waiting_.find(line);
    if (it == waiting_.end()) return;
    const std::vector<uint32_t> slots = std::move(it->second);
    waiting_.erase(it);
    for (const uint32_t slot : slots) {
      Wait& w = waits_.at(slot);
      w.ready = std::max(w.ready, fill);
      if (--w.lines == 0) done->read_done(slot, w.ready);
    }
  }

 private:
  struct Wait {
    uint32_t lines;
    uint64_t ready;
  };
  Tally& tally_;
  uint32_t core_, line_bytes_, latency_;
  std::map<uint64_t, std::vector<uint32_t>> waiting_;
  std::map<uint32_t, Wait> waits_;
};

}  // namespace

TEST_CASE("a replacement L1 that forwards every line to the L2 reaches it, and the L2 sees exactly its requests",
          "[module][swap][memory]") {
  const std::string path = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method("validity-bit", opt.method, err));
  HwConfig cfg = load_preset("small", "test");
  REQUIRE_FALSE(cfg.memory.ideal);
  const TlmStyle tlm = GENERATE(TlmStyle::LooselyTimed, TlmStyle::ApproximatelyTimed);
  cfg.memory.tlm = tlm;
  INFO("tlm " << tlm_style_name(tlm));

  auto run = [&](bool replaced, std::vector<Tally>* made, std::map<uint64_t, int32_t>& answers) {
    auto src = open_trace(path);
    const SceneAndBvh sb = load_trace_scene(src->header());
    src->set_triangle_count(sb.scene.size());
    CycleRunOptions options;
    if (replaced)
      options.units.l1_cache = [made](const char* name, uint32_t core, const HwConfig& c) {
        return std::make_unique<ForwardingL1>(name, core, c.memory.l1.line_bytes, c.memory.l1.hit_latency,
                                              made->at(core));
      };
    const RayResultSink sink = [&](const TraceRay&, const RayOutcome& out, uint64_t, uint64_t index) {
      answers[index] = out.answer;
    };
    return run_cycle_replay([&](TraceRay& ray) { return src->next(ray); }, sb.scene, sb.bvh, opt, cfg, sink, options);
  };
  std::map<uint64_t, int32_t> builtin_answers, forwarded_answers;
  const CycleRunResult builtin = run(false, nullptr, builtin_answers);
  std::vector<Tally> l1s(cfg.cores);
  const CycleRunResult forwarded = run(true, &l1s, forwarded_answers);
  CHECK(forwarded_answers == builtin_answers);
  uint64_t requests = 0, pending = 0;
  for (const Tally& l1 : l1s) {
    CHECK(l1.requests > 0);  // every core's replacement was made and used
    requests += l1.requests;
    pending += l1.pending_lines;
  }
  // Every line request reached the L2, and some had to wait for DRAM.
  const uint64_t l2_accesses = forwarded.hw["memory"]["port"]["l2"]["accesses"].get<uint64_t>();
  CHECK(requests > 0);
  CHECK(l2_accesses == requests);
  CHECK(pending > 0);
  CHECK(forwarded.hw["memory"]["port"]["l2"]["misses"].get<uint64_t>() > 0);
  // With no L1 to filter them the L2 sees more requests than the built-in L1s' misses.
  CHECK(l2_accesses > builtin.hw["memory"]["port"]["l2"]["accesses"].get<uint64_t>());
  CHECK(forwarded.counters.cycles > 0);
}

namespace {

/// The L2 and everything behind it: every line `latency` cycles after its request.
class FixedLatencyL2 final : public sc_core::sc_module, public LineReadIf {
 public:
  /// `requests` (by core) outlives it.
  FixedLatencyL2(sc_core::sc_module_name n, std::vector<uint64_t>& requests, uint32_t latency)
      : sc_core::sc_module(n), requests_(requests), latency_(latency) {}
  uint64_t read_line(uint64_t, uint64_t t, uint32_t core) override {
    ++requests_.at(core);
    return t + latency_;
  }

 private:
  std::vector<uint64_t>& requests_;
  uint32_t latency_;
};

}  // namespace

TEST_CASE("a replacement L2 bound in place of the built-in one takes every L1 miss of every core",
          "[module][swap][memory]") {
  const std::string path = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method("validity-bit", opt.method, err));
  const HwConfig cfg = load_preset("small", "test");
  auto src = open_trace(path);
  const SceneAndBvh sb = load_trace_scene(src->header());
  src->set_triangle_count(sb.scene.size());
  std::vector<int32_t> want;
  {
    FunctionalReplayer replayer(sb.scene, sb.bvh, opt);
    auto f = open_trace(path);
    f->set_triangle_count(sb.scene.size());
    TraceRay tr;
    while (f->next(tr)) want.push_back(replayer.replay(tr).answer);
  }
  std::vector<uint64_t> requests(cfg.cores, 0);
  CycleRunOptions options;
  options.units.l2_cache = [&requests](const char* name, const HwConfig&) {
    return std::make_unique<FixedLatencyL2>(name, requests, 40);
  };
  std::vector<int32_t> got(want.size(), -2);
  const RayResultSink sink = [&](const TraceRay&, const RayOutcome& out, uint64_t, uint64_t index) {
    got.at(index) = out.answer;
  };
  const CycleRunResult run =
      run_cycle_replay([&](TraceRay& ray) { return src->next(ray); }, sb.scene, sb.bvh, opt, cfg, sink, options);
  CHECK(got == want);
  const nlohmann::json& mem = run.hw["memory"]["port"];
  // Each core's L1 misses, and nothing else, reached the replacement.
  for (uint32_t c = 0; c < cfg.cores; ++c) {
    INFO("core " << c);
    CHECK(requests[c] > 0);
    CHECK(requests[c] == mem["l1"]["per_core"][c]["misses"].get<uint64_t>());
  }
  CHECK(mem["l2"]["replaced"] == true);
  CHECK(mem["l2"]["accesses"] == 0);
  CHECK(run.counters.cycles > 0);
}

namespace {

/// Never gives a line its cycle.
class PendingL2 final : public sc_core::sc_module, public LineReadIf {
 public:
  explicit PendingL2(sc_core::sc_module_name n) : sc_core::sc_module(n) {}
  uint64_t read_line(uint64_t, uint64_t, uint32_t) override { return kPendingCycle; }
};

}  // namespace

TEST_CASE("a replacement L2 that answers a line kPendingCycle stops the run with its slots reported stuck",
          "[module][swap][memory]") {
  const std::string path = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";
  auto src = open_trace(path);
  const SceneAndBvh sb = load_trace_scene(src->header());
  src->set_triangle_count(sb.scene.size());
  CycleRunOptions options;
  options.units.l2_cache = [](const char* name, const HwConfig&) { return std::make_unique<PendingL2>(name); };
  CHECK_THROWS_WITH(run_cycle_replay([&](TraceRay& ray) { return src->next(ray); }, sb.scene, sb.bvh,
                                     ReplayOptions{}, load_preset("small", "test"), {}, options),
                    Catch::Matchers::Contains("the run stopped making progress") &&
                        Catch::Matchers::Contains("waiting since cycle"));
}
