// The library prices what it simulates: an accelerator embedded in a user's own
// sc_main gives, in hw_json(), the energy and area `vbsim replay --mode cycle
// --stats` gives for the same trace, preset and method; a replaced unit that
// declares its operation inventory (hw/unit_inventory.h) is priced with it, one
// that declares none is marked not priced (docs/energy.md).
#include <catch2/catch.hpp>

#include <memory>

#include "../system/run_vbsim.h"
#include "datapath/datapath_ops.h"
#include "energy/tech_file.h"
#include "hw/accelerator.h"
#include "hw/core/pipeline_units.h"
#include "hw/observe/hw_energy.h"
#include "hw/simulation_context.h"
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

/// The bundled trace through an accelerator built as a user's sc_main builds
/// it (small preset, `cores` cores unless 0, validity bit), with `units`; its hw_json() after the run,
/// with the run's box and triangle tests as `box_tests`, `triangle_tests`.
nlohmann::json embedded_run(const AcceleratorUnits& units, const std::string& tech = "", uint32_t cores = 0) {
  const SimulationContext context;
  auto source = open_trace(kTrace);
  const SceneAndBvh sb = load_trace_scene(source->header());
  source->set_triangle_count(sb.scene.size());
  HwConfig cfg = load_preset("small", "test");
  if (cores) cfg.cores = cores;
  Accelerator acc("accelerator", cfg, sb.scene, sb.bvh, validity_bit(), units);
  if (!tech.empty()) acc.set_technology(tech);
  acc.set_feed([&](TraceRay& ray) { return source->next(ray); });
  sc_core::sc_start();
  acc.check();
  nlohmann::json hw = acc.hw_json();
  hw["box_tests"] = acc.replayer().stats().total().traversal.box_tests;
  hw["triangle_tests"] = acc.replayer().stats().total().traversal.triangle_tests;
  return hw;
}

/// A box unit of one's own that declares nothing: the built-in datapath, unpipelined timing aside.
class UndeclaredBoxUnit final : public sc_core::sc_module, public BoxUnitIf {
 public:
  explicit UndeclaredBoxUnit(sc_core::sc_module_name n) : sc_core::sc_module(n) {}
  BoxAnswer test_boxes(const BoxOp& op) override {
    BoxAnswer a = BoxUnit::compute(op);
    a.schedule = {op.ready, op.ready + 8};
    return a;
  }
};

}  // namespace

TEST_CASE("an embedded accelerator's hw_json() prices the run as vbsim replay --mode cycle --stats does",
          "[module][energy]") {
  const nlohmann::json hw = embedded_run({});
  const auto dir = test::scratch_dir("embedded_pricing");
  const std::string stats = (dir / "s.json").string();
  const test::RunResult r =
      test::run_vbsim("replay " + kTrace + " -q --mode cycle --preset small -m validity-bit --stats " + stats);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json replay = nlohmann::json::parse(test::read_file(stats))["hw"];
  REQUIRE(hw["cycles"] == replay["cycles"]);
  REQUIRE(hw.contains("energy"));
  REQUIRE(hw.contains("area"));
  CHECK(hw["energy"]["tech"] == default_tech_path());
  CHECK(hw["energy"]["per_ray_pj"].get<double>() == replay["energy"]["per_ray_pj"].get<double>());
  CHECK(hw["energy"]["total_pj"].get<double>() == replay["energy"]["total_pj"].get<double>());
  CHECK(hw["energy"]["dynamic_pj"] == replay["energy"]["dynamic_pj"]);
  CHECK(hw["area"]["chip_mm2"].get<double>() == replay["area"]["chip_mm2"].get<double>());
  CHECK_FALSE(hw["energy"].contains("replaced_units"));  // nothing replaced, nothing to say
}

TEST_CASE("an embedded accelerator prices with the technology file it is given", "[module][energy]") {
  const std::string tech7 = std::string(VBSIM_SOURCE_DIR) + "/model/energy/tech/7nm.json";
  const nlohmann::json hw = embedded_run({}, tech7);
  CHECK(hw["energy"]["tech"] == tech7);
  CHECK(hw["area"]["tech"] == tech7);
  // The box units' operators at 7 nm, by hand: two boxes' tests and the set-up.
  const TechFile t = load_tech_file(tech7);
  CHECK(hw["area"]["per_instance_mm2"]["box_unit"].get<double>() ==
        Approx(t.area_mm2(2 * box_test_ops()) + t.area_mm2(box_setup_ops())));
}

TEST_CASE("a replaced box unit that declares its operations is priced with them", "[module][energy]") {
  AcceleratorUnits units;
  units.box_unit = reduced_precision_box_unit(23);  // 23 bits: the built-in answers and cycles, more operations
  const nlohmann::json hw = embedded_run(units);
  const nlohmann::json builtin = embedded_run({});
  REQUIRE(hw["cycles"] == builtin["cycles"]);
  const TechFile t = load_tech_file(default_tech_path());
  // 12 int adds and 6 selects more per box tested: 12 x 0.1 + 6 x 0.025 = 1.35 pJ each.
  const OpCounts extra = ReducedPrecisionBoxUnit::rounding_ops();
  CHECK(t.energy_pj(extra) == Approx(1.35));
  const double box_tests = hw["box_tests"].get<double>();
  REQUIRE(box_tests > 0);
  CHECK(hw["energy"]["dynamic_pj"]["box"].get<double>() - builtin["energy"]["dynamic_pj"]["box"].get<double>() ==
        Approx(box_tests * 1.35));
  // Each box unit (issue interval 1, two boxes an operation) has the rounding's operators twice more:
  // 2 x (12 x 0.00031633 + 6 x 0.00007908) mm2.
  const double more = 2 * (12 * 0.00031633 + 6 * 7.908e-05);
  CHECK(hw["area"]["per_instance_mm2"]["box_unit"].get<double>() -
            builtin["area"]["per_instance_mm2"]["box_unit"].get<double>() ==
        Approx(more));
  const double units_count = hw["area"]["instances"]["box_unit"].get<double>();
  CHECK(hw["area"]["chip_mm2"].get<double>() - builtin["area"]["chip_mm2"].get<double>() == Approx(units_count * more));
  REQUIRE(hw["energy"]["replaced_units"].size() == 1);
  CHECK(hw["energy"]["replaced_units"][0]["unit"] == "box_unit");
  CHECK(hw["energy"]["replaced_units"][0]["instance"] == "accelerator.core_0.box_unit");
  CHECK(hw["energy"]["replaced_units"][0]["priced"] == true);
  CHECK(hw["energy"]["priced"] == true);
  CHECK(hw["area"]["priced"] == true);
}

TEST_CASE("a replaced triangle tester that declares its operations is priced with them", "[module][energy]") {
  AcceleratorUnits units;
  units.triangle_tester = reduced_precision_triangle_tester(23, TesterKind::ThreeHalfPlane);
  const nlohmann::json hw = embedded_run(units);
  const nlohmann::json builtin = embedded_run({});
  REQUIRE(hw["cycles"] == builtin["cycles"]);
  REQUIRE(hw["energy"]["priced"] == true);
  // 27 int adds more per triangle tested (nine coordinates rounded): 2.7 pJ each at 45 nm.
  CHECK(load_tech_file(default_tech_path()).energy_pj(ReducedPrecisionTriangleTester::rounding_ops()) == Approx(2.7));
  const double triangle_tests = hw["triangle_tests"].get<double>();
  REQUIRE(triangle_tests > 0);
  CHECK(hw["energy"]["dynamic_pj"]["triangle"].get<double>() -
            builtin["energy"]["dynamic_pj"]["triangle"].get<double>() ==
        Approx(triangle_tests * 2.7));
  // Each tester (issue interval 1) has 27 int adders more: 27 x 0.00031633 mm2.
  CHECK(hw["area"]["per_instance_mm2"]["triangle_tester"].get<double>() -
            builtin["area"]["per_instance_mm2"]["triangle_tester"].get<double>() ==
        Approx(27 * 0.00031633));
  // The other units are the built-in ones, priced as before.
  CHECK(hw["energy"]["dynamic_pj"]["box"] == builtin["energy"]["dynamic_pj"]["box"]);
}

TEST_CASE("a replaced unit that declares no operations is marked not priced, never priced as the built-in one",
          "[module][energy]") {
  AcceleratorUnits units;
  units.box_unit = [](const char* name, uint32_t, const HwConfig&) { return std::make_unique<UndeclaredBoxUnit>(name); };
  const nlohmann::json hw = embedded_run(units);
  CHECK(hw["energy"]["priced"] == false);
  CHECK(hw["area"]["priced"] == false);
  REQUIRE(hw["energy"]["replaced_units"].size() == 1);
  CHECK(hw["energy"]["replaced_units"][0] ==
        nlohmann::json({{"unit", "box_unit"}, {"instance", "accelerator.core_0.box_unit"}, {"priced", false}}));
  CHECK(hw["area"]["replaced_units"] == hw["energy"]["replaced_units"]);
  CHECK(hw["energy"]["dynamic_pj"]["box"].get<double>() == 0);
  CHECK(hw["area"]["per_instance_mm2"]["box_unit"].get<double>() == 0);
  // The rest is priced as usual.
  CHECK(hw["energy"]["dynamic_pj"]["triangle"].get<double>() > 0);
  CHECK(hw["area"]["per_instance_mm2"]["triangle_tester"].get<double>() > 0);
  CHECK_THAT(hw_energy_lines(hw["energy"], hw["area"]),
             Catch::Contains("not priced: accelerator.core_0.box_unit (a replaced box_unit that declares no operation "
                             "inventory"));
}

namespace {

/// A core's whole memory: every read takes 20 cycles (no arrays to price).
class FixedLatencyMemory final : public sc_core::sc_module, public MemoryReadIf {
 public:
  explicit FixedLatencyMemory(sc_core::sc_module_name n) : sc_core::sc_module(n) {}
  uint64_t read(uint64_t, uint32_t, uint64_t now, uint32_t) override { return now + 20; }
};

}  // namespace

TEST_CASE("a replaced L1 is not priced: the built-in L1's array and accesses are left out", "[module][energy]") {
  AcceleratorUnits units;
  units.l1_cache = [](const char* name, uint32_t, const HwConfig&) { return std::make_unique<FixedLatencyMemory>(name); };
  const nlohmann::json hw = embedded_run(units, "", 1);  // one core: its memory path is the replacement alone
  CHECK(hw["energy"]["priced"] == false);
  CHECK(hw["energy"]["replaced_units"][0] ==
        nlohmann::json({{"unit", "l1_cache"}, {"instance", "accelerator.core_0.l1_cache"}, {"priced", false}}));
  CHECK(hw["energy"]["dynamic_pj"]["l1"].get<double>() == 0);
  CHECK(hw["area"]["per_instance_mm2"]["l1_cache"].get<double>() == 0);
  CHECK(hw["area"]["chip_mm2"].get<double>() > 0);
  CHECK_THAT(hw_energy_lines(hw["energy"], hw["area"]),
             Catch::Contains("not priced: accelerator.core_0.l1_cache (a replaced l1_cache (only a box unit"));
}
