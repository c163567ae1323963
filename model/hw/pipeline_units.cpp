#include "hw/pipeline_units.h"

namespace vbsim::hw {

PipelineUnit::PipelineUnit(sc_core::sc_module_name name, const UnitConfig& config)
    : sc_core::sc_module(name), target("target"), config_(config), latency_(config.latency),
      pipes_(config, counters_, sc_core::sc_module::name()) {
  target.bind(*this);
  declare_stat("ops", "operations", "operations issued", counters_.ops);
  declare_stat("pipeline_full_cycles", "cycles",
               "cycles operations waited for a free pipeline after their operands were ready", counters_.wait_cycles);
}

nlohmann::json PipelineUnit::parameters() const {
  return {{"count", config_.count}, {"latency", config_.latency}, {"issue_interval", config_.issue_interval}};
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
