// The pipelined units of a ray-test core as SystemC modules: the box unit (both
// child boxes of a node per operation), the triangle tester (the patent's
// three-half-plane test, or Möller–Trumbore or pbrt-watertight: one triangle
// per operation, emitting the front/back bit) and the intersection-avoidance
// unit (one suspect's epsilon tests). Each wraps a reservation table of its
// `count` pipelines (UnitPipelines) for the schedule and computes its result
// with the plain-C++ datapath (RayBoxTester, the tester of its kind,
// avoidance_decide), reached through BoxUnitIf, TriangleTesterIf and
// AvoidanceUnitIf (hw/unit_interfaces.h) at its export `target`.
//
// schedule_inline() is the schedule alone, without the virtual call: the
// scheduler times a built-in unit with it and computes the result with the
// slot's latched datapath state (BvhStepper's BuiltinUnits), which answers as
// the module's interface call does (testbench/unit/pipeline_units_test.cpp).
#pragma once
#include <cstdint>
#include <string>

#include <systemc>

#include "datapath/avoidance_unit.h"
#include "datapath/testers.h"
#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/observe/stat_provider.h"
#include "hw/unit_interfaces.h"
#include "hw/unit_pipelines.h"

namespace vbsim::hw {

/// The timing shared by the three: `count` pipelines of one latency.
class PipelineUnit : public sc_core::sc_module, public StatProvider {
 public:
  PipelineUnit(sc_core::sc_module_name name, const UnitConfig& config);

  UnitSchedule schedule_inline(uint64_t ready, uint64_t now) {
    const uint64_t issue = pipes_.issue(ready, now);
    return {issue, issue + latency_};
  }

  const UnitConfig& config() const { return config_; }
  const UnitCounters& counters() const { return counters_; }
  nlohmann::json parameters() const override;

 private:
  UnitConfig config_;
  uint32_t latency_;
  UnitCounters counters_;
  UnitPipelines pipes_;
};

/// Tests every child box of one node per operation (2, 4 or 8; the root's box at dispatch).
class BoxUnit final : public PipelineUnit, public BoxUnitIf {
 public:
  sc_core::sc_export<BoxUnitIf> target;

  BoxUnit(sc_core::sc_module_name name, const UnitConfig& config);
  /// RayBoxTester's answer (op.latched, or the ray's own when null).
  BoxAnswer test_boxes(const BoxOp& op) override;
  /// The result without the schedule (no pipeline reserved).
  static BoxAnswer compute(const BoxOp& op);
  const char* unit_kind() const override { return "BoxUnit"; }
};

/// Tests one triangle per operation with `tester`, emitting the front/back bit.
class TriangleTester final : public PipelineUnit, public TriangleTesterIf {
 public:
  sc_core::sc_export<TriangleTesterIf> target;

  TriangleTester(sc_core::sc_module_name name, const UnitConfig& config, TesterKind tester);
  /// The `tester` kind's answer (set up for the operation's ray).
  TriangleAnswer test_triangle(const TriangleOp& op) override;
  /// The result without the schedule, with tester kind `kind`.
  static TriangleAnswer compute(TesterKind kind, const TriangleOp& op);
  const char* unit_kind() const override { return "TriangleTester"; }
  nlohmann::json parameters() const override;
  TesterKind tester() const { return tester_; }

 private:
  TesterKind tester_;
};

/// Decides one suspect candidate per operation (the patent's normal and
/// epsilon checks, policy `config.policy`); idle unless the method is
/// validity-bit with a policy that tests (`in_use`).
class AvoidanceUnit final : public PipelineUnit, public AvoidanceUnitIf {
 public:
  sc_core::sc_export<AvoidanceUnitIf> target;

  AvoidanceUnit(sc_core::sc_module_name name, const UnitConfig& config, const AvoidanceConfig& avoidance,
                bool in_use);
  /// avoidance_decide() under the operation's configuration.
  AvoidanceAnswer decide(const AvoidanceOp& op) override;
  const char* unit_kind() const override { return "AvoidanceUnit"; }
  nlohmann::json parameters() const override;
  bool in_use() const { return in_use_; }

 private:
  AvoidanceConfig avoidance_;
  bool in_use_;
};

}  // namespace vbsim::hw
