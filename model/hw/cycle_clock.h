// CycleClock: the accelerator's clock as SystemC time. Cycle k of a run is at
// SystemC time origin + k * period (period = 1e6 / clock_mhz ps, rounded to the
// 1 ps resolution). The scheduler runs ahead of SystemC time by up to a quantum,
// so a unit answering for a future cycle annotates the difference as a TLM-2.0
// delay; these conversions are exact in whole periods, and a delay that ends
// between two clock edges is taken at the next edge (a response is seen by the
// clocked logic of the accelerator at its next cycle).
#pragma once
#include <cstdint>

#include <systemc>

namespace vbsim::hw {

class CycleClock {
 public:
  explicit CycleClock(double clock_mhz) : period_(1e6 / clock_mhz, sc_core::SC_PS) {}

  /// The run's cycle 0 is the current SystemC time.
  void start_now() { origin_ = sc_core::sc_time_stamp(); }
  const sc_core::sc_time& period() const { return period_; }
  const sc_core::sc_time& origin() const { return origin_; }

  /// The cycle SystemC time is at (whole periods since the origin).
  uint64_t now() const { return (sc_core::sc_time_stamp() - origin_).value() / period_.value(); }
  /// The delay from the current SystemC time to cycle `cycle` (>= now()).
  sc_core::sc_time delay_to(uint64_t cycle) const { return cycles(cycle - now()); }
  /// `n` cycles as SystemC time.
  sc_core::sc_time cycles(uint64_t n) const { return sc_core::sc_time::from_value(period_.value() * n); }
  /// The cycle a delay of `delay` from the current SystemC time ends at, rounded up to a whole cycle.
  uint64_t cycle_after(const sc_core::sc_time& delay) const {
    const uint64_t since = (sc_core::sc_time_stamp() - origin_ + delay).value();
    return (since + period_.value() - 1) / period_.value();
  }

 private:
  sc_core::sc_time period_;
  sc_core::sc_time origin_ = sc_core::SC_ZERO_TIME;
};

}  // namespace vbsim::hw
