// The pipelined units of a ray-test core as SystemC modules: the box unit (both
// child boxes of a node per operation), the triangle tester (the patent's
// three-half-plane test, or Möller–Trumbore or pbrt-watertight: one triangle
// per operation, emitting the front/back bit) and the intersection-avoidance
// unit (one suspect's epsilon tests). Each wraps a reservation table of its
// `count` pipelines (UnitPipelines) and is reached through PipelineIf
// (hw/unit_interfaces.h) at its export `target`.
//
// What the tester and the avoidance unit compute is the datapath's
// (ThreeHalfPlaneTester and its siblings, avoidance_decide, run by the slots'
// BvhSteppers); these modules name which datapath unit the core uses and time
// it. schedule_inline() is the same as schedule() without the virtual call, for
// the scheduler when the bound unit is one of these.
#pragma once
#include <cstdint>
#include <string>

#include <systemc>

#include "datapath/avoidance_unit.h"
#include "datapath/testers.h"
#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/stat_provider.h"
#include "hw/unit_interfaces.h"
#include "hw/unit_pipelines.h"

namespace vbsim::hw {

class PipelineUnit : public sc_core::sc_module, public PipelineIf, public StatProvider {
 public:
  sc_core::sc_export<PipelineIf> target;

  PipelineUnit(sc_core::sc_module_name name, const UnitConfig& config);

  UnitSchedule schedule(uint64_t ready, uint64_t now) final { return schedule_inline(ready, now); }
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

/// Tests both child boxes of one node per operation.
class BoxUnit final : public PipelineUnit {
 public:
  BoxUnit(sc_core::sc_module_name name, const UnitConfig& config) : PipelineUnit(name, config) {}
  const char* unit_kind() const override { return "BoxUnit"; }
};

/// Tests one triangle per operation with `tester`, emitting the front/back bit.
class TriangleTester final : public PipelineUnit {
 public:
  TriangleTester(sc_core::sc_module_name name, const UnitConfig& config, TesterKind tester)
      : PipelineUnit(name, config), tester_(tester) {}
  const char* unit_kind() const override { return "TriangleTester"; }
  nlohmann::json parameters() const override;
  TesterKind tester() const { return tester_; }

 private:
  TesterKind tester_;
};

/// Decides one suspect candidate per operation (the patent's normal and
/// epsilon checks, policy `config.policy`); idle unless the method is
/// validity-bit with a policy that tests (`in_use`).
class AvoidanceUnit final : public PipelineUnit {
 public:
  AvoidanceUnit(sc_core::sc_module_name name, const UnitConfig& config, const AvoidanceConfig& avoidance,
                bool in_use)
      : PipelineUnit(name, config), avoidance_(avoidance), in_use_(in_use) {}
  const char* unit_kind() const override { return "AvoidanceUnit"; }
  nlohmann::json parameters() const override;
  bool in_use() const { return in_use_; }

 private:
  AvoidanceConfig avoidance_;
  bool in_use_;
};

}  // namespace vbsim::hw
