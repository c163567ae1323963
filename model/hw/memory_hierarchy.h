// The accelerator's cache hierarchy as a MemoryPort: a private L1 per core, a
// shared L2 and one DRAM channel (docs/memory-model.md has the timing rules).
//
// A read is split into the cache lines it spans; each line is looked up in the
// core's L1 at the read's cycle; the read's data are ready when its last line is.
// Latency of one line (no contention):
//   L1 hit:             now + l1.hit_latency
//   L1 miss, L2 hit:    now + l1.hit_latency + l2.hit_latency
//   L1 miss, L2 miss:   now + l1.hit_latency + l2.hit_latency + dram_latency
// plus, under load, the MSHR, outstanding-request and channel waits.
// The L2 is non-inclusive: its evictions leave the L1s alone.
#pragma once
#include <cstdint>
#include <vector>

#include "hw/cache_level.h"
#include "hw/dram_channel.h"
#include "hw/memory_port.h"

namespace vbsim::hw {

/// Throws std::invalid_argument naming the field ("memory.l1.ways: ...") when
/// `config` cannot describe a hierarchy for `cores` cores. Ideal memories pass.
void check_memory_config(const MemoryConfig& config, int cores);

class MemoryHierarchy final : public MemoryPort {
 public:
  /// `config` must pass check_memory_config.
  MemoryHierarchy(const MemoryConfig& config, int cores);

  uint64_t read(int core, uint64_t addr, uint32_t bytes, uint64_t now) override;
  nlohmann::json stats() const override;
  /// Asks the host's caches for the tag sets a read of `addr` by `core` looks up
  /// first (its first line in the L1 and the L2); changes nothing.
  void prefetch(int core, uint64_t addr) const {
    const uint64_t line = addr >> line_shift_;
    l1_[static_cast<size_t>(core)].tags().prefetch(line);
    l2_.tags().prefetch(line);
  }

 private:
  /// read() for an L1 of `L1Ways` and an L2 of `L2Ways` ways (0: any, read at run time).
  template <uint32_t L1Ways, uint32_t L2Ways>
  uint64_t read_shaped(int core, uint64_t addr, uint32_t bytes, uint64_t now);
  template <uint32_t L1Ways, uint32_t L2Ways>
  uint64_t read_line(CacheLevel& l1, uint64_t line, uint64_t now);
  template <uint32_t L2Ways>
  uint64_t read_l2(uint64_t line, uint64_t t);

  /// The associativities read() has a form for with the ways known at compile time.
  enum class Shape { Any, L1x4L2x8, L1x4L2x16 };

  MemoryConfig config_;
  Shape shape_;
  uint32_t line_shift_;
  std::vector<CacheLevel> l1_;  // one per core
  CacheLevel l2_;
  DramChannel dram_;
  uint64_t reads_ = 0, bytes_ = 0;
  uint64_t first_now_ = 0, last_ready_ = 0;
};

}  // namespace vbsim::hw
