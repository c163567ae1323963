// EngineTracer: what the scheduler records of a run for the VCD and the
// timeline (hw/observe/vcd_recorder.h, hw/observe/timeline_recorder.h): per
// core, the operations in flight in each unit, its busy slots and its reads in
// flight; per slot, its steps; the ray source's waiting and emitted rays; the
// chip's rays in flight and done. Called only when a recorder is set (one flag
// a step in the scheduler), out of line: it never changes a cycle.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <systemc>

#include "hw/core/unit_operations.h"
#include "hw/observe/timeline_recorder.h"
#include "hw/observe/vcd_recorder.h"

namespace vbsim::hw {

struct CoreBinding;

namespace engine_detail {

/// The hierarchical name of the module behind `iface`, or `fallback` when it is
/// not a module (an interface implemented by something else).
const char* instance_name(sc_core::sc_interface* iface, const std::string& fallback);

class EngineTracer {
 public:
  /// The units a core's operations are recorded for (CoreCounters' order).
  enum Unit { kBox, kTriangle, kAvoidance, kUnits };

  /// Either recorder may be null; with both null nothing is recorded.
  EngineTracer(TimelineRecorder* timeline, VcdRecorder* vcd) : timeline_(timeline), vcd_(vcd) {}
  bool on() const { return timeline_ || vcd_; }

  /// Declares the signals and tracks of `cores` (each with `slots_per_core`
  /// slots, `slots` in all) and of the ray source `source`.
  void set_up(const std::vector<CoreBinding>& cores, uint32_t slots_per_core, uint32_t slots,
              sc_core::sc_interface* source);

  /// A ray that entered the source's buffer at `entered`, was emitted (its
  /// emission started) at `emitted` and left for a slot at `at`.
  void source_ray(uint64_t entered, uint64_t emitted, uint64_t at);
  /// Slot `slot` of core `core`, holding ray `ray`: its step `name` over
  /// [start, end), whose read (if any) took [asked, ready).
  void step(uint32_t slot, uint32_t core, int64_t ray, const char* name, uint64_t start, uint64_t end,
            uint64_t asked, uint64_t ready);
  /// One operation `op` of unit `unit` of core `core` for ray `ray`.
  void op(uint32_t core, int64_t ray, Unit unit, const UnitSchedule& op);
  /// A ray entering (+1) or leaving (-1) a slot of core `core` at `at`.
  void occupancy(uint32_t core, uint64_t at, int delta);

 private:
  /// Per core: the VCD signal (operations in flight) and timeline track of each
  /// unit, its busy-slot signal and its memory's track.
  struct CoreTrace {
    uint32_t unit_signal[kUnits], unit_track[kUnits];
    uint32_t busy_signal, memory_track;
    uint32_t reads_signal;  ///< reads of its slots issued, data not yet there
  };

  TimelineRecorder* timeline_;
  VcdRecorder* vcd_;
  std::vector<CoreTrace> core_trace_;
  std::vector<uint32_t> slot_track_;
  uint32_t rays_done_signal_ = VcdRecorder::kNoSignal, in_flight_signal_ = VcdRecorder::kNoSignal;
  uint32_t source_waiting_signal_ = VcdRecorder::kNoSignal, source_emitted_signal_ = VcdRecorder::kNoSignal;
};

}  // namespace engine_detail
}  // namespace vbsim::hw
