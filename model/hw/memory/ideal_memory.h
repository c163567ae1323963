// IdealMemory: a memory with a fixed latency and unlimited bandwidth, bound to
// every core's memory port in place of the caches (memory.ideal): no stalls but
// the latency. Used to find the units' own bounds.
#pragma once
#include <cstdint>

#include <systemc>

#include "hw/memory/memory_interfaces.h"
#include "hw/observe/stat_provider.h"

namespace vbsim::hw {

class IdealMemory final : public sc_core::sc_module, public MemoryReadIf, public StatProvider {
 public:
  sc_core::sc_export<MemoryReadIf> target;  ///< bound by every core

  IdealMemory(sc_core::sc_module_name name, uint32_t latency)
      : sc_core::sc_module(name), target("target"), latency_(latency < 1 ? 1 : latency) {
    target.bind(*this);
    declare_stat("reads", "reads", "reads by all cores", reads_);
    declare_stat("bytes", "bytes", "bytes read", bytes_);
  }

  uint64_t read(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot) override {
    return read_inline(addr, bytes, now, slot);
  }
  uint64_t read_inline(uint64_t, uint32_t bytes, uint64_t now, uint32_t) {
    ++reads_;
    bytes_ += bytes;
    return now + latency_;
  }

  const char* unit_kind() const override { return "IdealMemory"; }
  nlohmann::json parameters() const override { return {{"latency", latency_}}; }
  uint32_t latency() const { return latency_; }
  uint64_t reads() const { return reads_; }
  uint64_t bytes() const { return bytes_; }

 private:
  uint32_t latency_;
  uint64_t reads_ = 0, bytes_ = 0;
};

}  // namespace vbsim::hw
