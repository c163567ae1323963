// The SystemC side of the cycle-level model: one SC_METHOD that advances a
// CycleEngine and re-triggers itself with next_trigger() at the next cycle it
// has work for, so SystemC's simulated time is the accelerator's clock
// (one cycle = the clock period, 1e6 / clock_mhz ps rounded to the 1 ps
// resolution). No sc_clock, no per-cycle activation, no signals in the pipelines.
//
// Temporal decoupling: one activation at cycle c processes every event in
// [c, c + quantum_cycles) and then sleeps until max(c + quantum, next event);
// after the last ray, one more activation lands SystemC time exactly on the
// final cycle, so (end - start) of a run is cycles * period. quantum_cycles = 1
// makes every event cycle an activation; the engine's results never depend on it.
//
// Several runs in one process: SystemC 2.3.4 elaborates once, so the driver
// module is created once (on the first run, before the first sc_start) and kept;
// each run hands it an engine, notifies its event and calls sc_start(), which
// returns when nothing is left to do (starvation). Simulated time keeps
// growing across runs; each run measures from its own start. A VCD can only be
// opened before the first sc_start of the process.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "hw/cycle_engine.h"
#include "hw/hw_config.h"

namespace vbsim::hw {

struct DriveOptions {
  std::string vcd;                        ///< VCD file of the key values (empty: none)
  const std::atomic<bool>* stop = nullptr;  ///< set (e.g. by SIGINT) to end the run early
  /// Called about every quarter second of wall time with the engine (e.g. a progress bar).
  std::function<void(const CycleEngine&)> progress;
};

struct DriveResult {
  double start_ps = 0, end_ps = 0;  ///< SystemC time at the run's start and end
  uint64_t cycles = 0;              ///< (end - start) / period, as SystemC measured it
  uint64_t activations = 0;         ///< activations of the SC_METHOD
  double period_ps = 0;
};

/// Runs `engine` to the end under SystemC. Exceptions thrown inside the
/// process are rethrown here. Throws std::runtime_error when a VCD is asked
/// for after simulation has started in this process.
DriveResult drive_with_systemc(CycleEngine& engine, const HwConfig& cfg, const DriveOptions& options);

}  // namespace vbsim::hw
