// The triangle tester's latency and issue interval derived from its arithmetic
// (hw/core/tester_timing.h, docs/hw-model.md "Tester latency from its arithmetic"):
// each tester's longest dependency chain counted by hand from its code, priced
// with the stated operator latencies; the configuration's derive, override and
// operator fields.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "datapath/datapath_ops.h"
#include "hw/core/tester_timing.h"
#include "hw/hw_config.h"
#include "replay/replay_config.h"

using namespace vbsim;
using namespace vbsim::hw;

TEST_CASE("each tester's latency is its dependency chain at the stated operator latencies", "[hwconfig][tester-timing]") {
  const OperatorLatencies op;  // SimTRaX: fadd 2, fmul 2, fcmp 1, fsel 1; fma 4, fdiv 16
  // three-half-plane: a = v - o (add 2), shear (mul 2, add 2), edge function
  // (mul 2, add 2), t_scaled (mul 2, add 2, add 2), t = t_scaled / det (div 16),
  // tmin < t < tmax (cmp 1): 33.
  CHECK(derived_triangle_latency(TesterKind::ThreeHalfPlane, op) == 2 + 2 + 2 + 2 + 2 + 2 + 2 + 2 + 16 + 1);
  // Moller-Trumbore: e2 (add 2), p = d x e2 (mul 2, add 2), det = dot (mul 2,
  // add 2, add 2), 1 / det (div 16), v (mul 2), u + v (add 2), <= 1 (cmp 1): 33.
  CHECK(derived_triangle_latency(TesterKind::MollerTrumbore, op) == 2 + 2 + 2 + 2 + 2 + 2 + 16 + 2 + 2 + 1);
  // pbrt-watertight: q (add 2), shear (mul 2, add 2), difference of products
  // (mul 2, fma 4, add 2), det (add 2, add 2), 1 / det (div 16), |inv_det| (sel 1)
  // and delta_t's last product (mul 2), t > delta_t (cmp 1): 38.
  CHECK(derived_triangle_latency(TesterKind::PbrtWatertight, op) == 2 + 2 + 2 + 2 + 4 + 2 + 2 + 2 + 16 + 1 + 2 + 1);
  // Another operator table prices the same chains: a divider of 8 cycles takes
  // 8 off every tester (one divide on each chain).
  OperatorLatencies fast = op;
  fast.fdiv = 8;
  for (TesterKind k : {TesterKind::ThreeHalfPlane, TesterKind::MollerTrumbore, TesterKind::PbrtWatertight})
    CHECK(derived_triangle_latency(k, fast) == derived_triangle_latency(k, op) - 8);
}

TEST_CASE("a tester's chain uses only operations its count has", "[hwconfig][tester-timing]") {
  for (TesterKind k : {TesterKind::ThreeHalfPlane, TesterKind::MollerTrumbore, TesterKind::PbrtWatertight}) {
    const OpCounts path = triangle_test_critical_path(k);
    const OpCounts all = triangle_test_ops(k);
    CHECK(path.fadd <= all.fadd);
    CHECK(path.fmul <= all.fmul);
    CHECK(path.fma <= all.fma);
    CHECK(path.fdiv <= all.fdiv);
    CHECK(path.fcmp <= all.fcmp);
    CHECK(path.fsel <= all.fsel);
    CHECK(path.total() < all.total());
  }
}

TEST_CASE("the issue interval follows the operations over the operators", "[hwconfig][tester-timing]") {
  // Fully pipelined (one operator per operation): 1 for every tester.
  for (TesterKind k : {TesterKind::ThreeHalfPlane, TesterKind::MollerTrumbore, TesterKind::PbrtWatertight})
    CHECK(derived_triangle_issue_interval(k, 0) == 1);
  // With the three-half-plane's 63 operators: Moller-Trumbore's 60 fit, pbrt's 134 take 3 issues.
  CHECK(triangle_test_ops(TesterKind::ThreeHalfPlane).total() == 63);
  CHECK(derived_triangle_issue_interval(TesterKind::ThreeHalfPlane, 63) == 1);
  CHECK(derived_triangle_issue_interval(TesterKind::MollerTrumbore, 63) == 1);
  CHECK(derived_triangle_issue_interval(TesterKind::PbrtWatertight, 63) == 3);
  CHECK(derived_triangle_issue_interval(TesterKind::ThreeHalfPlane, 1) == 63);
}

TEST_CASE("derive, operators and operator latencies in the configuration, and a latency that overrides them", "[hwconfig][tester-timing]") {
  HwConfig c;
  apply_hw_config(nlohmann::json::parse(R"({"triangle": {"derive": true, "operators": 63,
                                            "operator_latency": {"fdiv": 10}}})"),
                  "f.json", c);
  CHECK(for_tester(c, TesterKind::ThreeHalfPlane).triangle.latency == 33 - 16 + 10);
  CHECK(for_tester(c, TesterKind::PbrtWatertight).triangle.latency == 38 - 16 + 10);
  CHECK(for_tester(c, TesterKind::PbrtWatertight).triangle.issue_interval == 3);
  // The JSON form keeps the derivation and round-trips.
  const nlohmann::json j = hw_config_json(for_tester(c, TesterKind::MollerTrumbore));
  CHECK(j["triangle"]["derive"] == true);
  CHECK(j["triangle"]["latency"] == 27);
  CHECK(j["triangle"]["operator_latency"]["fdiv"] == 10);
  HwConfig back;
  apply_hw_config(j, "f.json", back);
  CHECK(for_tester(back, TesterKind::PbrtWatertight).triangle.latency == 32);
  // A latency given without derive fixes the timing for every tester.
  apply_hw_config(nlohmann::json::parse(R"({"triangle": {"latency": 25}})"), "g.json", c);
  CHECK(!c.triangle_timing.derive);
  for (TesterKind k : {TesterKind::ThreeHalfPlane, TesterKind::MollerTrumbore, TesterKind::PbrtWatertight})
    CHECK(for_tester(c, k).triangle.latency == 25);
  // Bad values name their field.
  HwConfig d;
  CHECK_THROWS_WITH(apply_hw_config(nlohmann::json::parse(R"({"triangle": {"operator_latency": {"fdiv": 0}}})"),
                                    "h.json", d),
                    Catch::Contains("field 'hw.triangle.operator_latency.fdiv'"));
  CHECK_THROWS_WITH(apply_hw_config(nlohmann::json::parse(R"({"triangle": {"operator_latency": {"fsqr": 3}}})"),
                                    "h.json", d),
                    Catch::Contains("field 'hw.triangle.operator_latency.fsqr': unknown field"));
  CHECK_THROWS_WITH(apply_hw_config(nlohmann::json::parse(R"({"triangle": {"derive": 1}})"), "h.json", d),
                    Catch::Contains("field 'hw.triangle.derive'"));
}
