// MemoryRig: the accelerator's memory modules (every core's L1Cache, the
// L2Cache and the built-in Dram behind its TLM-2.0 socket, or the IdealMemory),
// elaborated inside an Accelerator of `cores` cores in a simulation context of
// their own (elaboration only), and read directly as a core does, for tests that compute the
// answers by hand. Reads happen at SystemC time 0 (no simulation runs): the
// TLM delay annotations carry the cycles.
#pragma once
#include <memory>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "hw/accelerator.h"
#include "hw/simulation_context.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim::hw::test {

class MemoryRig {
 public:
  /// Throws what the Accelerator throws for an invalid `memory` (std::invalid_argument naming the field).
  MemoryRig(const MemoryConfig& memory, int cores) {
    HwConfig cfg;
    cfg.cores = static_cast<uint32_t>(cores < 0 ? 0 : cores);
    cfg.memory = memory;
    acc_ = std::make_unique<Accelerator>("accelerator", cfg, scene_, bvh_, ReplayOptions{});
    sc_core::sc_get_curr_simcontext()->elaborate();  // binds the ports (no simulation starts)
  }
  ~MemoryRig() { acc_.reset(); }

  /// Core `core`'s read of `bytes` at `addr` at cycle `now`: the cycle its data are there.
  uint64_t read(int core, uint64_t addr, uint32_t bytes, uint64_t now) {
    if (core < 0 || static_cast<size_t>(core) >= acc_->cores())
      throw std::out_of_range("memory: read by core " + std::to_string(core));
    RayTestCore& c = acc_->core(static_cast<size_t>(core));
    if (IdealMemory* ideal = acc_->ideal_memory()) return ideal->read(addr, bytes, now, c.first_slot());
    return c.l1()->read(addr, bytes, now, c.first_slot());
  }
  nlohmann::json stats() const { return acc_->memory_stats(); }
  Accelerator& accelerator() { return *acc_; }

 private:
  SimulationContext context_;
  Scene scene_;
  Bvh bvh_;
  std::unique_ptr<Accelerator> acc_;
};

// L1: 2 sets x 2 ways, hit 2; L2: 4 sets x 4 ways, hit 10; DRAM 100 cycles,
// 16 bytes per cycle (a 64-byte line takes 4 cycles on the channel).
// Unloaded: L1 hit 2, L2 hit 2 + 10 = 12, DRAM 2 + 10 + 100 = 112 cycles.
inline MemoryConfig small_config() {
  MemoryConfig m;
  m.l1 = {256, 2, 64, 2, 2};
  m.l2 = {1024, 4, 64, 10, 4};
  m.dram_latency = 100;
  m.dram_bytes_per_cycle = 16;
  m.dram_max_outstanding = 8;
  return m;
}

// The same with a channel so fast that back-to-back lines do not queue.
inline MemoryConfig fast_channel_config() {
  MemoryConfig m = small_config();
  m.dram_bytes_per_cycle = 65536;
  return m;
}

inline std::unique_ptr<MemoryRig> make_memory(const MemoryConfig& memory, int cores) {
  return std::make_unique<MemoryRig>(memory, cores);
}

}  // namespace vbsim::hw::test
