// The memory the cycle-level model's ray-test units fetch BVH nodes and
// triangles from. A port answers "a read of `bytes` at `addr` by core `core`,
// issued at cycle `now`, has its data at cycle R" and counts what it did.
//
// Contract for every implementation:
//  - Calls come in non-decreasing `now` (the engine handles events in time
//    order); the returned ready cycle is >= now + 1.
//  - The answer depends only on the sequence of calls, so a run is repeatable.
//  - Addresses are byte addresses of the BVH layout (hw/bvh_address_map.h of the
//    engine): nodes, then triangles; a read may span several cache lines.
#pragma once
#include <cstdint>
#include <memory>

#include <nlohmann/json.hpp>

namespace vbsim::hw {

/// One cache level. Sizes in bytes; latencies in core clock cycles.
struct CacheConfig {
  uint32_t size_bytes = 0;
  uint32_t ways = 0;
  uint32_t line_bytes = 64;
  uint32_t hit_latency = 0;  ///< cycles from request to data on a hit
  uint32_t mshrs = 0;        ///< misses in flight at once (outstanding-miss limit)
};

/// The memory system of the accelerator: a private L1 per core, a shared L2, DRAM.
struct MemoryConfig {
  bool ideal = false;          ///< every read takes ideal_latency cycles, no caches
  uint32_t ideal_latency = 1;  ///< cycles per read of the ideal memory
  CacheConfig l1{16 * 1024, 4, 64, 2, 8};
  CacheConfig l2{1024 * 1024, 8, 64, 14, 32};
  uint32_t dram_latency = 120;        ///< cycles from an L2 miss to its line arriving (unloaded)
  double dram_bytes_per_cycle = 16;   ///< DRAM bandwidth in bytes per core clock cycle
  uint32_t dram_max_outstanding = 32; ///< DRAM requests in flight at once
};

class MemoryPort {
 public:
  virtual ~MemoryPort() = default;
  /// The cycle at which `bytes` at `addr` are available to `core` (see the contract above).
  virtual uint64_t read(int core, uint64_t addr, uint32_t bytes, uint64_t now) = 0;
  /// Counters as JSON (the `hw.memory` section of the stats).
  virtual nlohmann::json stats() const = 0;
};

/// A memory with a fixed latency and unlimited bandwidth: no stalls but the latency.
class IdealMemory final : public MemoryPort {
 public:
  explicit IdealMemory(uint32_t latency) : latency_(latency < 1 ? 1 : latency) {}
  uint64_t read(int, uint64_t, uint32_t bytes, uint64_t now) override {
    ++reads_;
    bytes_ += bytes;
    return now + latency_;
  }
  nlohmann::json stats() const override {
    return {{"model", "ideal"}, {"latency", latency_}, {"reads", reads_}, {"bytes", bytes_}};
  }

 private:
  uint32_t latency_;
  uint64_t reads_ = 0, bytes_ = 0;
};

/// The memory `config` describes for `cores` cores: IdealMemory when `ideal`,
/// otherwise the L1/L2/DRAM hierarchy (docs/memory-model.md). Throws
/// std::invalid_argument starting with the field ("memory.l1.ways: ...") when
/// the hierarchy's settings are invalid.
std::unique_ptr<MemoryPort> make_memory(const MemoryConfig& config, int cores);

}  // namespace vbsim::hw
