#include "hw/scheduler/engine_tracer.h"

#include "hw/core/ray_test_core.h"
#include "hw/scheduler/cycle_engine.h"

namespace vbsim::hw::engine_detail {

const char* instance_name(sc_core::sc_interface* iface, const std::string& fallback) {
  const auto* o = dynamic_cast<const sc_core::sc_object*>(iface);
  return o ? o->name() : fallback.c_str();
}

void EngineTracer::set_up(const std::vector<CoreBinding>& cores, uint32_t slots_per_core, uint32_t slots,
                          sc_core::sc_interface* source) {
  static const char* kSignal = "ops_in_flight";
  for (const CoreBinding& c : cores) {
    const std::string core = c.core->name();
    const std::string units[kUnits] = {instance_name(c.box, core + ".box_unit"),
                                       instance_name(c.triangle, core + ".triangle_tester"),
                                       instance_name(c.avoidance, core + ".avoidance_unit")};
    CoreTrace t{};
    for (int u = 0; u < kUnits; ++u) {
      t.unit_signal[u] = vcd_ ? vcd_->signal(units[u], kSignal) : VcdRecorder::kNoSignal;
      const std::string thread = units[u].substr(units[u].rfind('.') + 1);
      t.unit_track[u] = timeline_ ? timeline_->track(core, thread, units[u]) : TimelineRecorder::kNoTrack;
    }
    t.busy_signal = vcd_ ? vcd_->signal(core, "busy_slots") : VcdRecorder::kNoSignal;
    t.reads_signal = vcd_ ? vcd_->signal(core, "reads_in_flight") : VcdRecorder::kNoSignal;
    t.memory_track = timeline_ ? timeline_->track(core, "memory reads") : TimelineRecorder::kNoTrack;
    core_trace_.push_back(t);
  }
  if (timeline_)
    for (uint32_t i = 0; i < slots; ++i)
      slot_track_.push_back(
          timeline_->track(cores[i / slots_per_core].core->name(), "slot " + std::to_string(i % slots_per_core)));
  if (vcd_) {
    rays_done_signal_ = vcd_->signal("accelerator", "rays_done");
    in_flight_signal_ = vcd_->signal("accelerator", "rays_in_flight");
    const std::string name = instance_name(source, "accelerator.ray_source");
    source_waiting_signal_ = vcd_->signal(name, "rays_waiting");
    source_emitted_signal_ = vcd_->signal(name, "rays_emitted");
  }
}

void EngineTracer::source_ray(uint64_t entered, uint64_t emitted, uint64_t at) {
  if (!vcd_) return;
  vcd_->add(source_waiting_signal_, entered, +1);
  vcd_->add(source_waiting_signal_, at, -1);
  vcd_->add(source_emitted_signal_, emitted, +1);
}

void EngineTracer::step(uint32_t slot, uint32_t core, int64_t ray, const char* name, uint64_t start, uint64_t end,
                        uint64_t asked, uint64_t ready) {
  if (vcd_ && ready > asked) {
    vcd_->add(core_trace_[core].reads_signal, asked, +1);
    vcd_->add(core_trace_[core].reads_signal, ready, -1);
  }
  if (!timeline_) return;
  timeline_->add(slot_track_[slot], name, start, end, ray);
  if (ready > asked) timeline_->add(core_trace_[core].memory_track, name, asked, ready, ray);
}

void EngineTracer::op(uint32_t core, int64_t ray, Unit unit, const UnitSchedule& op) {
  static const char* kNames[kUnits] = {"box", "triangle", "avoidance"};
  const CoreTrace& t = core_trace_[core];
  if (vcd_) {
    vcd_->add(t.unit_signal[unit], op.issue, +1);
    vcd_->add(t.unit_signal[unit], op.done, -1);
  }
  if (timeline_) timeline_->add(t.unit_track[unit], kNames[unit], op.issue, op.done, ray);
}

void EngineTracer::occupancy(uint32_t core, uint64_t at, int delta) {
  if (!vcd_) return;
  vcd_->add(core_trace_[core].busy_signal, at, delta);
  vcd_->add(in_flight_signal_, at, delta);
  if (delta < 0) vcd_->add(rays_done_signal_, at, 1);
}

}  // namespace vbsim::hw::engine_detail
