// The reduced-precision example units (reduced_precision/reduced_precision_units.h)
// bound through AcceleratorUnits on the bundled trace: a box unit with bounds
// rounded outward keeps every hit and does at least the built-in work; a
// triangle tester on rounded vertices changes hits, counted against the
// functional replay; at 23 bits both are the built-in units exactly.
#include <catch2/catch.hpp>

#include <vector>

#include "reduced_precision/precision_study.h"
#include "reduced_precision/reduced_precision_units.h"
#include "replay/replay_run.h"
#include "trace/trace_source.h"

using namespace vbsim;
using namespace vbsim::hw;

namespace {

const std::string kTrace = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";

ReplayOptions validity_bit() {
  ReplayOptions opt;
  std::string err;
  parse_method("validity-bit", opt.method, err);
  return opt;
}

/// The functional replay's answers, by trace position.
std::vector<int32_t> functional_answers(const ReplayOptions& opt) {
  auto src = open_trace(kTrace);
  const SceneAndBvh sb = load_trace_scene(src->header());
  src->set_triangle_count(sb.scene.size());
  FunctionalReplayer replayer(sb.scene, sb.bvh, opt);
  std::vector<int32_t> out;
  TraceRay tr;
  while (src->next(tr)) out.push_back(replayer.replay(tr).answer);
  return out;
}

}  // namespace

TEST_CASE("a box unit with bounds rounded outward keeps every hit and tests at least as many boxes",
          "[module][precision]") {
  const ReplayOptions opt = validity_bit();
  const HwConfig cfg = load_preset("small", "test");
  const std::vector<int32_t> exact = functional_answers(opt);
  std::vector<int32_t> builtin_answers;
  const PrecisionRun builtin = precision_run(kTrace, cfg, opt, {}, &exact, &builtin_answers);
  CHECK(builtin.changed == 0);  // the built-in cycle-level run answers as the functional one
  // One operation per root box, two box tests per node operation.
  CHECK(builtin.box_ops == builtin.rays + (builtin.box_tests - builtin.rays) / 2);
  for (const int bits : {4, 8, 12, 16, 20, 23}) {
    INFO(bits << " bits");
    AcceleratorUnits units;
    units.box_unit = reduced_precision_box_unit(bits);
    const PrecisionRun r = precision_run(kTrace, cfg, opt, units, &exact, nullptr);
    CHECK(r.rays == builtin.rays);
    CHECK(r.changed == 0);
    CHECK(r.self_hits == builtin.self_hits);
    CHECK(r.box_tests >= builtin.box_tests);
    CHECK(r.triangle_tests >= builtin.triangle_tests);
    CHECK(r.box_ops == r.rays + (r.box_tests - r.rays) / 2);  // counted by the scheduler for the replacement
    CHECK(r.cycles > 0);
    if (bits == 23) CHECK(r.cycles == builtin.cycles);  // nothing rounded: the built-in unit exactly
    if (bits <= 8) {  // coarse bounds: measurably more work
      CHECK(r.box_tests > builtin.box_tests);
      CHECK(r.triangle_tests > builtin.triangle_tests);
    }
    if (bits == 4) CHECK(r.cycles > builtin.cycles);
  }
}

TEST_CASE("a triangle tester on rounded vertices changes hits, counted against the functional replay",
          "[module][precision]") {
  const ReplayOptions opt = validity_bit();
  const HwConfig cfg = load_preset("small", "test");
  const std::vector<int32_t> exact = functional_answers(opt);
  const PrecisionRun builtin = precision_run(kTrace, cfg, opt, {}, &exact, nullptr);
  uint64_t previous = ~uint64_t{0};
  for (const int bits : {8, 12, 16, 23}) {
    INFO(bits << " bits");
    AcceleratorUnits units;
    units.triangle_tester = reduced_precision_triangle_tester(bits, opt.tester);
    const PrecisionRun r = precision_run(kTrace, cfg, opt, units, &exact, nullptr);
    CHECK(r.rays == builtin.rays);
    CHECK(r.triangle_ops == r.triangle_tests);  // one operation per triangle test
    if (bits == 23) {
      CHECK(r.changed == 0);
      CHECK(r.cycles == builtin.cycles);
      CHECK(r.self_hits == builtin.self_hits);
    } else {
      CHECK(r.changed > 0);
      CHECK(r.self_hits > builtin.self_hits);  // vertices moved under the origins of their secondary rays
    }
    CHECK(r.changed <= previous);  // more bits, fewer changed rays
    previous = r.changed;
  }
}

TEST_CASE("the precision study lists the built-in run first and each replacement after it", "[module][precision]") {
  const std::vector<PrecisionRun> runs =
      precision_study(kTrace, load_preset("small", "test"), validity_bit(), {8}, {12});
  REQUIRE(runs.size() == 3);
  CHECK(runs[0].units == "built-in");
  CHECK(runs[1].units == "box 8 bits");
  CHECK(runs[2].units == "triangle 12 bits");
  CHECK(runs[1].changed == 0);
  CHECK(runs[2].changed > 0);
}
