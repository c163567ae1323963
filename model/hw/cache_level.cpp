#include "hw/cache_level.h"

namespace vbsim::hw {

CacheLevel::CacheLevel(const CacheConfig& config)
    : tags_(config.size_bytes / (config.ways * config.line_bytes), config.ways),
      hit_latency_(config.hit_latency),
      mshrs_(config.mshrs),
      flight_line_(config.mshrs, LruCache::kNoLine),
      fill_(config.mshrs, 0),
      order_(config.mshrs, 0),
      pending_from_(config.mshrs),
      in_flight_per_set_(tags_.sets(), 0) {
  index_bits_ = 0;
  while ((uint64_t{1} << index_bits_) < config.mshrs) ++index_bits_;
  index_mask_ = (uint64_t{1} << index_bits_) - 1;
  ring_.assign(size_t{1} << index_bits_, 0);
  for (uint32_t i = 0; i < config.mshrs; ++i) ring_[i] = i;  // all free at cycle 0, in index order
  due_.reserve(config.mshrs);
}

void CacheLevel::hold(uint64_t line, uint64_t fill) {
  // The front leaves the ring; its line, if still in flight, filled before
  // this miss started: present now.
  const uint32_t mshr = static_cast<uint32_t>(ring_[head_] & index_mask_);
  if (pending_from_ == 0) install(mshr);
  else --pending_from_;
  head_ = static_cast<uint32_t>((head_ + 1) & index_mask_);

  flight_line_[mshr] = line;
  fill_[mshr] = fill;
  order_[mshr] = ++claims_;
  ++in_flight_per_set_[tags_.set_of(line)];

  // Back in at its place from the tail (cycles stay below 2^(64 - index_bits_),
  // i.e. 2^52). Its fill is after every retired horizon, so it lands in the
  // pending tail; fills arrive nearly in order, so this moves few keys.
  const uint64_t key = (fill << index_bits_) | mshr;
  uint32_t k = mshrs_ - 1;
  for (; k > pending_from_ && ring_at(k - 1) > key; --k) ring_at(k) = ring_at(k - 1);
  ring_at(k) = key;
  next_fill_ = fill_of_key(ring_at(pending_from_));
}

void CacheLevel::retire_slow(uint64_t horizon) {
  // The due fills, from pending_from_ on, in (fill cycle, claim order) order:
  // the ring orders equal fills by index, so a run of them is re-sorted by claim.
  while (pending_from_ < mshrs_ && fill_of_key(ring_at(pending_from_)) <= horizon) {
    const uint64_t fill = fill_of_key(ring_at(pending_from_));
    uint32_t end = pending_from_ + 1;
    while (end < mshrs_ && fill_of_key(ring_at(end)) == fill) ++end;
    if (end == pending_from_ + 1) {
      install(static_cast<uint32_t>(ring_at(pending_from_) & index_mask_));
    } else {
      due_.clear();
      for (uint32_t k = pending_from_; k < end; ++k) {
        const uint32_t i = static_cast<uint32_t>(ring_at(k) & index_mask_);
        size_t at = due_.size();
        due_.push_back(i);
        for (; at > 0 && order_[due_[at - 1]] > order_[i]; --at) due_[at] = due_[at - 1];
        due_[at] = i;
      }
      for (const uint32_t i : due_) install(i);
    }
    pending_from_ = end;
  }
  next_fill_ = pending_from_ < mshrs_ ? fill_of_key(ring_at(pending_from_)) : ~uint64_t{0};
}

}  // namespace vbsim::hw
