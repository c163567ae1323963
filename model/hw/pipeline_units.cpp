#include "hw/pipeline_units.h"

namespace vbsim::hw {

PipelineUnit::PipelineUnit(sc_core::sc_module_name name, const UnitConfig& config, const char* op)
    : sc_core::sc_module(name), target("target"), config_(config), latency_(config.latency), op_(op),
      pipes_(config, counters_) {
  target.bind(*this);
  declare_stat("ops", "operations", "operations issued", counters_.ops);
  declare_stat("pipeline_full_cycles", "cycles",
               "cycles operations waited for a free pipeline after their operands were ready", counters_.wait_cycles);
}

nlohmann::json PipelineUnit::parameters() const {
  return {{"count", config_.count}, {"latency", config_.latency}, {"issue_interval", config_.issue_interval}};
}

void PipelineUnit::set_tracing(VcdRecorder* vcd, TimelineRecorder* timeline) {
  vcd_ = vcd;
  timeline_ = timeline;
  vcd_signal_ = vcd ? vcd->signal(name(), "ops_in_flight") : VcdRecorder::kNoSignal;
  const std::string core = get_parent_object() ? get_parent_object()->name() : name();
  track_ = timeline ? timeline->track(core, basename()) : TimelineRecorder::kNoTrack;
  traced_ = vcd_signal_ != VcdRecorder::kNoSignal || track_ != TimelineRecorder::kNoTrack;
}

void PipelineUnit::trace(const UnitSchedule& s) {
  if (vcd_) {
    vcd_->add(vcd_signal_, s.issue, +1);
    vcd_->add(vcd_signal_, s.done, -1);
  }
  if (timeline_) timeline_->add(track_, op_, s.issue, s.done, -1);
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
