#include "hw/lru_cache.h"

namespace vbsim::hw {

LruCache::LruCache(uint32_t sets, uint32_t ways)
    : sets_(sets),
      ways_(ways),
      set_mask_(sets > 1 && (sets & (sets - 1)) == 0 ? sets - 1 : 0),
      tags_(static_cast<size_t>(sets) * ways, kNoLine),
      stamps_(static_cast<size_t>(sets) * ways, 0) {}

bool LruCache::touch(uint64_t line) {
  const size_t base = static_cast<size_t>(set_of(line)) * ways_;
  for (size_t w = base; w < base + ways_; ++w)
    if (tags_[w] == line) {
      stamps_[w] = ++clock_;
      return true;
    }
  return false;
}

bool LruCache::contains(uint64_t line) const {
  const size_t base = static_cast<size_t>(set_of(line)) * ways_;
  for (size_t w = base; w < base + ways_; ++w)
    if (tags_[w] == line) return true;
  return false;
}

uint64_t LruCache::install(uint64_t line) {
  const size_t base = static_cast<size_t>(set_of(line)) * ways_;
  size_t victim = base;
  for (size_t w = base; w < base + ways_; ++w) {
    if (tags_[w] == kNoLine) {
      victim = w;
      break;
    }
    if (stamps_[w] < stamps_[victim]) victim = w;
  }
  const uint64_t replaced = tags_[victim];
  tags_[victim] = line;
  stamps_[victim] = ++clock_;
  return replaced;
}

}  // namespace vbsim::hw
