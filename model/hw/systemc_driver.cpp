#include "hw/systemc_driver.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <systemc>

namespace vbsim::hw {

namespace {

using sc_core::sc_time;

class EngineDriver : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(EngineDriver);
  explicit EngineDriver(sc_core::sc_module_name name) : sc_core::sc_module(name) {
    SC_METHOD(activate);
    sensitive << kick_;
    dont_initialize();
  }

  void trace(sc_core::sc_trace_file* tf) {
    sc_core::sc_trace(tf, cycle_, "cycle");
    sc_core::sc_trace(tf, rays_done_, "rays_done");
    sc_core::sc_trace(tf, in_flight_, "rays_in_flight");
    sc_core::sc_trace(tf, box_ops_, "box_ops");
    sc_core::sc_trace(tf, triangle_ops_, "triangle_ops");
    sc_core::sc_trace(tf, avoidance_ops_, "avoidance_ops");
    sc_core::sc_trace(tf, memory_wait_, "memory_wait_cycles");
  }

  DriveResult run(CycleEngine& engine, const HwConfig& cfg, const DriveOptions& options) {
    engine_ = &engine;
    options_ = &options;
    period_ = sc_time(1e6 / cfg.clock_mhz, sc_core::SC_PS);
    quantum_ = cfg.quantum_cycles;
    origin_ = sc_core::sc_time_stamp();
    activations_ = 0;
    error_ = nullptr;
    last_progress_ = std::chrono::steady_clock::now();
    kick_.notify(sc_core::SC_ZERO_TIME);
    sc_core::sc_start();
    engine_ = nullptr;
    if (error_) std::rethrow_exception(error_);
    DriveResult r;
    r.start_ps = origin_.to_seconds() * 1e12;
    r.end_ps = sc_core::sc_time_stamp().to_seconds() * 1e12;
    r.cycles = cycle_now();
    r.activations = activations_;
    r.period_ps = period_.to_seconds() * 1e12;
    return r;
  }

 private:
  uint64_t cycle_now() const { return (sc_core::sc_time_stamp() - origin_).value() / period_.value(); }

  void activate() {
    try {
      ++activations_;
      const uint64_t now = cycle_now();
      if (options_->stop && options_->stop->load(std::memory_order_relaxed)) engine_->stop();
      engine_->advance(now + quantum_);
      sample(now);
      if (!engine_->finished()) {
        const uint64_t next = std::max(now + quantum_, engine_->next_event_cycle());
        next_trigger(period_ * static_cast<double>(next - now));
      } else if (!engine_->stopped() && engine_->counters().cycles > now) {
        next_trigger(period_ * static_cast<double>(engine_->counters().cycles - now));  // land on the last cycle
      }
    } catch (...) {
      error_ = std::current_exception();
      engine_->stop();
    }
  }

  void sample(uint64_t now) {
    const HwCounters& c = engine_->counters();
    cycle_ = now;
    rays_done_ = c.rays;
    in_flight_ = engine_->rays_in_flight();
    box_ops_ = c.box.ops;
    triangle_ops_ = c.triangle.ops;
    avoidance_ops_ = c.avoidance.ops;
    memory_wait_ = c.memory_wait_cycles;
    if (options_->progress && (activations_ & 255) == 0) {
      const auto t = std::chrono::steady_clock::now();
      if (t - last_progress_ > std::chrono::milliseconds(250)) {
        last_progress_ = t;
        options_->progress(*engine_);
      }
    }
  }

  sc_core::sc_event kick_;
  CycleEngine* engine_ = nullptr;
  const DriveOptions* options_ = nullptr;
  sc_time period_, origin_;
  uint64_t quantum_ = 1, activations_ = 0;
  std::exception_ptr error_;
  std::chrono::steady_clock::time_point last_progress_;
  // Values a VCD shows (sampled at every activation).
  uint64_t cycle_ = 0, rays_done_ = 0, in_flight_ = 0, box_ops_ = 0, triangle_ops_ = 0, avoidance_ops_ = 0,
           memory_wait_ = 0;
};

EngineDriver* g_driver = nullptr;

}  // namespace

DriveResult drive_with_systemc(CycleEngine& engine, const HwConfig& cfg, const DriveOptions& options) {
  const bool started = sc_core::sc_start_of_simulation_invoked();
  if (!g_driver) {
    if (started) throw std::runtime_error("hw: SystemC simulation already started without the engine driver");
    g_driver = new EngineDriver("vbsim_engine_driver");  // lives as long as the simulation context
  }
  sc_core::sc_trace_file* tf = nullptr;
  if (!options.vcd.empty()) {
    if (started)
      throw std::runtime_error("--vcd: a VCD can only be written by the first simulation run of the process");
    std::string base = options.vcd;
    if (base.size() > 4 && base.compare(base.size() - 4, 4, ".vcd") == 0) base.resize(base.size() - 4);
    tf = sc_core::sc_create_vcd_trace_file(base.c_str());
    if (!tf) throw std::runtime_error(options.vcd + ": cannot write VCD");
    tf->set_time_unit(1, sc_core::SC_PS);
    g_driver->trace(tf);
  }
  DriveResult r = g_driver->run(engine, cfg, options);
  if (tf) sc_core::sc_close_vcd_trace_file(tf);
  return r;
}

}  // namespace vbsim::hw
