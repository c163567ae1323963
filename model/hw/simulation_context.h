// SimulationContext: a fresh SystemC simulation context for one run, made
// current for as long as the object lives (the previous one is current again
// afterwards). SystemC elaborates once per context and never after its first
// sc_start, so each cycle-level run, each test design and each `vbsim hw`
// elaboration gets its own; every module of the run must be destroyed before
// the context is.
#pragma once
#include <systemc>

namespace vbsim::hw {

class SimulationContext {
 public:
  SimulationContext() : previous_(sc_core::sc_curr_simcontext), previous_default_(sc_core::sc_default_global_context) {
    mine_ = new sc_core::sc_simcontext();
    sc_core::sc_curr_simcontext = mine_;
    sc_core::sc_default_global_context = mine_;
  }
  ~SimulationContext() {
    delete mine_;
    sc_core::sc_curr_simcontext = previous_;
    sc_core::sc_default_global_context = previous_default_;
  }
  SimulationContext(const SimulationContext&) = delete;
  SimulationContext& operator=(const SimulationContext&) = delete;

 private:
  sc_core::sc_simcontext* previous_;
  sc_core::sc_simcontext* previous_default_;
  sc_core::sc_simcontext* mine_;
};

}  // namespace vbsim::hw
