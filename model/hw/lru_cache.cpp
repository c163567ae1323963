#include "hw/lru_cache.h"

namespace vbsim::hw {

LruCache::LruCache(uint32_t sets, uint32_t ways)
    : sets_(sets),
      ways_(ways),
      sets_pow2_((sets & (sets - 1)) == 0),
      set_mask_(sets - 1),
      lines_(static_cast<size_t>(sets) * ways, kNoLine) {}

}  // namespace vbsim::hw
