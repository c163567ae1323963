#include "hw/cache_level.h"

namespace vbsim::hw {

CacheLevel::CacheLevel(const CacheConfig& config)
    : tags_(config.size_bytes / (config.ways * config.line_bytes), config.ways),
      hit_latency_(config.hit_latency),
      mshrs_(config.mshrs) {
  uint32_t bits = 0;
  while ((uint64_t{1} << bits) < config.mshrs) ++bits;
  ring_.assign(size_t{1} << bits, 0);  // every MSHR free from cycle 0
  ring_mask_ = (uint32_t{1} << bits) - 1;
}

}  // namespace vbsim::hw
