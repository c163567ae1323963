#include "hw/lru_cache.h"

namespace vbsim::hw {

LruCache::LruCache(uint32_t sets, uint32_t ways)
    : sets_(sets),
      ways_(ways),
      set_mask_(sets > 1 && (sets & (sets - 1)) == 0 ? sets - 1 : 0),
      ways_of_sets_(static_cast<size_t>(sets) * ways) {}

bool LruCache::touch(uint64_t line) {
  const size_t base = static_cast<size_t>(set_of(line)) * ways_;
  for (size_t w = base; w < base + ways_; ++w)
    if (ways_of_sets_[w].line == line) {
      ways_of_sets_[w].stamp = ++clock_;
      return true;
    }
  return false;
}

bool LruCache::contains(uint64_t line) const {
  const size_t base = static_cast<size_t>(set_of(line)) * ways_;
  for (size_t w = base; w < base + ways_; ++w)
    if (ways_of_sets_[w].line == line) return true;
  return false;
}

uint64_t LruCache::install(uint64_t line) {
  const size_t base = static_cast<size_t>(set_of(line)) * ways_;
  Way* victim = &ways_of_sets_[base];
  for (Way* w = victim; w != &ways_of_sets_[base] + ways_; ++w) {
    if (w->line == kNoLine) {
      victim = w;
      break;
    }
    if (w->stamp < victim->stamp) victim = w;
  }
  const uint64_t replaced = victim->line;
  victim->line = line;
  victim->stamp = ++clock_;
  return replaced;
}

}  // namespace vbsim::hw
