#include "hw/core/pipeline_units.h"

#include <optional>

namespace vbsim::hw {

PipelineUnit::PipelineUnit(sc_core::sc_module_name name, const UnitConfig& config)
    : sc_core::sc_module(name), config_(config), latency_(config.latency),
      pipes_(config, counters_, sc_core::sc_module::name()) {
  declare_stat("ops", "operations", "operations issued", counters_.ops);
  declare_stat("pipeline_full_cycles", "cycles",
               "cycles operations waited for a free pipeline after their operands were ready", counters_.wait_cycles);
}

nlohmann::json PipelineUnit::parameters() const {
  return {{"count", config_.count},
          {"latency", config_.latency},
          {"issue_interval", config_.issue_interval},
          {"share", config_.share}};
}

BoxUnit::BoxUnit(sc_core::sc_module_name name, const UnitConfig& config)
    : PipelineUnit(name, config), target("target") {
  target.bind(*this);
}

BoxAnswer BoxUnit::compute(const BoxOp& op) {
  std::optional<RayBoxTester> own;
  const RayBoxTester* box = op.latched;
  if (!box) box = &own.emplace(*op.ray);
  BoxAnswer a;
  if (op.narrow && op.node_record) a.met = op.narrow->hits(*op.node_record, op.tmax, a.entry[0], a.entry[1]);
  else if (op.node_record) a.met = box->hits(*op.node_record, op.tmax, a.entry[0], a.entry[1]);
  else if (op.node4_record) a.met = box->hits(*op.node4_record, op.tmax, a.entry);
  else if (op.node8_record) a.met = box->hits(*op.node8_record, op.tmax, a.entry);
  else a.met = box->hits(*op.root, op.tmax) ? 1u : 0u;
  return a;
}

BoxAnswer BoxUnit::test_boxes(const BoxOp& op) {
  BoxAnswer a = compute(op);
  a.schedule = schedule_inline(op.ready, op.now);
  return a;
}

TriangleTester::TriangleTester(sc_core::sc_module_name name, const UnitConfig& config, TesterKind tester)
    : PipelineUnit(name, config), target("target"), tester_(tester) {
  target.bind(*this);
}

TriangleAnswer TriangleTester::compute(TesterKind kind, const TriangleOp& op) {
  TriangleAnswer a;
  switch (kind) {
    case TesterKind::MollerTrumbore:
      a.candidate = MollerTrumboreTester(*op.ray).intersect(*op.triangle, op.tmax, a.hit);
      break;
    case TesterKind::PbrtWatertight:
      a.candidate = PbrtWatertightTester(*op.ray).intersect(*op.triangle, op.tmax, a.hit);
      break;
    case TesterKind::ThreeHalfPlane:
    default: a.candidate = ThreeHalfPlaneTester(*op.ray).intersect(*op.triangle, op.tmax, a.hit); break;
  }
  return a;
}

TriangleAnswer TriangleTester::test_triangle(const TriangleOp& op) {
  TriangleAnswer a = compute(tester_, op);
  a.schedule = schedule_inline(op.ready, op.now);
  return a;
}

AvoidanceUnit::AvoidanceUnit(sc_core::sc_module_name name, const UnitConfig& config,
                             const AvoidanceConfig& avoidance, bool in_use)
    : PipelineUnit(name, config), target("target"), avoidance_(avoidance), in_use_(in_use) {
  target.bind(*this);
}

AvoidanceAnswer AvoidanceUnit::decide(const AvoidanceOp& op) {
  AvoidanceAnswer a;
  a.decision = avoidance_decide(op.config ? *op.config : avoidance_, *op.ray, *op.triangle, *op.candidate);
  a.schedule = schedule_inline(op.ready, op.now);
  return a;
}

nlohmann::json TriangleTester::parameters() const {
  nlohmann::json j = PipelineUnit::parameters();
  j["tester"] = tester_name(tester_);
  return j;
}

nlohmann::json AvoidanceUnit::parameters() const {
  nlohmann::json j = PipelineUnit::parameters();
  j["in_use"] = in_use_;
  j["policy"] = avoidance_policy_name(avoidance_.policy);
  j["eps_mode"] = epsilon_mode_name(avoidance_.eps_mode);
  if (avoidance_.eps_mode == EpsilonMode::Fixed) j["eps"] = avoidance_.eps;
  else j["guard_bits"] = avoidance_.guard_bits, j["min_exponent"] = avoidance_.min_exponent;
  j["tests"] = {{"normal", avoidance_.test_normal}, {"ray", avoidance_.test_ray},
                {"component", avoidance_.test_component}};
  return j;
}

}  // namespace vbsim::hw
