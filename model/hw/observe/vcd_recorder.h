// VcdRecorder: integer values of module instances (busy slots of a core,
// operations in flight in its units, outstanding L1 misses, rays done) at cycle
// resolution over a window of cycles, written as a VCD file for GTKWave.
//
// The model reserves work ahead of the cycle it handles (an operation is
// scheduled when the step that needs it is handled), so a value is recorded as
// changes (+k at the cycle it takes effect), in any order of cycles; write()
// reads them back sorted (VcdChangeLog, spilled to a temporary file beyond a
// chunk). Changes before the window form each value's starting level; those
// after the window are dropped. Signals are named by hierarchical instance name;
// a TraceScope keeps only the instances it names ("accelerator.core_3"). The
// file ends at the window's end or the run's, whichever comes first.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "hw/observe/trace_scope.h"
#include "hw/observe/vcd_change_log.h"

namespace vbsim::hw {

class VcdRecorder {
 public:
  static constexpr uint32_t kNoSignal = ~uint32_t{0};

  /// Records [first, first + cycles); `period_ps` is one cycle in the file's
  /// 1 ps time unit; `scope` the instances kept (empty: all). The changes are
  /// held in memory up to `spill_chunk` at a time, the rest in a temporary file
  /// (VcdChangeLog): memory stays bounded whatever the window.
  VcdRecorder(uint64_t first, uint64_t cycles, uint64_t period_ps, TraceScope scope,
              size_t spill_chunk = size_t{1} << 20);

  /// A signal `name` of instance `instance`: its id, or kNoSignal when the
  /// instance is outside the scope (add() then does nothing).
  uint32_t signal(const std::string& instance, const std::string& name);
  /// The value of `id` changes by `delta` at `cycle`.
  void add(uint32_t id, uint64_t cycle, int64_t delta) {
    if (id == kNoSignal || cycle >= end_) return;
    if (cycle < first_) base_[id] += delta;
    else changes_.add({cycle, id, delta});
  }
  /// Writes the VCD, ending after cycle `run_end` (the run's last) when that
  /// comes before the window's end; throws OutputError when the file cannot be written.
  /// Once only (it reads the changes back).
  void write(const std::string& path, uint64_t run_end);
  size_t signals() const { return names_.size(); }

 private:
  uint64_t first_, end_, period_ps_;
  TraceScope scope_;
  std::vector<std::string> instances_, names_;
  std::vector<int64_t> base_;
  VcdChangeLog changes_;
};

}  // namespace vbsim::hw
