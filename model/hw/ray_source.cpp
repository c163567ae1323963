#include "hw/ray_source.h"

namespace vbsim::hw {

namespace {

/// Emission-time method operations acting on `tr` (each costs emission_op_cycles).
uint32_t emission_ops(const SelfIntersectionMethod& m, const TraceRay& tr) {
  const bool child = tr.parent_prim >= 0, shadow = tr.kind == RayKind::Shadow;
  uint32_t ops = m.tmin;
  if (child) ops += m.offset_normal + m.offset_direction + m.offset_adaptive + m.offset_errbound;
  if (shadow && child) ops += m.shading_position || m.shading_position_always;
  if (shadow) ops += m.reverse_shadow;
  return ops;
}

}  // namespace

RaySource::RaySource(sc_core::sc_module_name name, const SourceConfig& config, FunctionalReplayer& replayer)
    : sc_core::sc_module(name), target("target"), config_(config), replayer_(replayer) {
  target.bind(*this);
  declare_stat("rays", "rays", "rays emitted", counters_.rays);
  declare_stat("busy_cycles", "cycles", "cycles spent emitting (issue interval, sign bits, emission operations)",
               counters_.busy_cycles);
  declare_stat("sign_bits_computed", "rays", "child rays whose parent sign bit the source computed",
               counters_.sign_bits_computed);
  declare_stat("emission_ops", "operations", "emission-time method operations (offsets, tmin, ...)",
               counters_.emission_ops);
  declare_stat("no_free_slot_cycles", "cycles", "cycles an emitted ray waited because every slot was busy",
               counters_.no_free_slot_cycles);
}

nlohmann::json RaySource::parameters() const {
  return {{"issue_interval", config_.issue_interval},
          {"sign_bit_cycles", config_.sign_bit_cycles},
          {"emission_op_cycles", config_.emission_op_cycles},
          {"method", replayer_.options().method.name()}};
}

bool RaySource::start_emission(uint64_t at, uint64_t& ready) {
  if (!feed_ || !feed_(tr_)) return false;  // end of the trace
  index_ = counters_.rays++;
  er_ = replayer_.emit(tr_);
  uint64_t cost = config_.issue_interval;
  if (tr_.sign < 0 && tr_.parent_prim >= 0) {
    cost += config_.sign_bit_cycles;
    ++counters_.sign_bits_computed;
  }
  const uint32_t ops = emission_ops(replayer_.options().method, tr_);
  counters_.emission_ops += ops;
  cost += uint64_t{ops} * config_.emission_op_cycles;
  counters_.busy_cycles += cost;
  ready = at + cost;
  return true;
}

}  // namespace vbsim::hw
