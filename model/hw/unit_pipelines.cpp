#include "hw/unit_pipelines.h"

#include <utility>

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace vbsim::hw {

namespace {
constexpr size_t kInitialWords = 16;  // 1024 cycles from the current event's block; grows on demand
}  // namespace

UnitPipelines::UnitPipelines(const UnitConfig& c, UnitCounters& totals, std::string owner)
    : count_(c.count < 1 ? 1 : c.count),
      latency_(c.latency),
      interval_(c.issue_interval < 1 ? 1 : c.issue_interval),
      words_per_pipe_(kInitialWords),
      word_mask_(kInitialWords - 1),
      ring_(count_ * kInitialWords),
      totals_(&totals), owner_(std::move(owner)) {}

uint64_t UnitPipelines::issue_general(uint64_t ready, uint32_t interval) {
  uint64_t best = ~uint64_t{0};
  uint32_t best_pipe = 0;
  for (uint32_t p = 0; p < count_; ++p) {
    // The first c >= ready with [c, c + interval) clear in pipeline p.
    uint64_t c = ready;
    for (uint64_t k = 0; k < interval;) {
      if (taken(p, c + k)) {
        c += k + 1;  // no fit starts at or before the taken cycle
        k = 0;
      } else {
        ++k;
      }
    }
    if (c < best) best = c, best_pipe = p;
  }
  for (uint64_t k = 0; k < interval; ++k) take(best_pipe, best + k);
  return best;
}

void UnitPipelines::move_to(uint64_t block) {
  const uint64_t left = std::min<uint64_t>(block - now_block_, words_per_pipe_);
  for (uint32_t p = 0; p < count_; ++p)
    for (uint64_t b = now_block_; b < now_block_ + left; ++b) ring_[size_t{p} * words_per_pipe_ + (b & word_mask_)] = 0;
  now_block_ = block;
}

void UnitPipelines::grow(uint64_t block) {
  if (block < now_block_)
    throw std::logic_error(fmt::format("{}: an operation ready at cycle {} or earlier, before the current event's "
                                       "cycle {} or later (a unit's operands cannot be ready in the past)",
                                       owner_, block * kWordBits + kWordBits - 1, now_block_ * kWordBits));
  size_t words = words_per_pipe_;
  while (block - now_block_ >= words) words *= 2;
  std::vector<uint64_t> ring(count_ * words, 0);
  for (uint32_t p = 0; p < count_; ++p)
    for (uint64_t b = now_block_; b < now_block_ + words_per_pipe_; ++b)  // the blocks the ring holds
      ring[size_t{p} * words + (b & (words - 1))] = ring_[size_t{p} * words_per_pipe_ + (b & word_mask_)];
  ring_.swap(ring);
  words_per_pipe_ = words;
  word_mask_ = words - 1;
}

}  // namespace vbsim::hw
