#include "hw/unit_pipelines.h"

#include <stdexcept>

namespace vbsim::hw {

namespace {
constexpr size_t kInitialWords = 16;  // 1024 cycles from the current event's block; grows on demand
}  // namespace

UnitPipelines::UnitPipelines(const UnitConfig& c, UnitCounters& totals)
    : count_(c.count < 1 ? 1 : c.count),
      latency_(c.latency),
      interval_(c.issue_interval < 1 ? 1 : c.issue_interval),
      words_per_pipe_(kInitialWords),
      word_mask_(kInitialWords - 1),
      ring_(count_ * kInitialWords),
      totals_(&totals) {}

uint64_t UnitPipelines::issue_general(uint64_t ready) {
  uint64_t best = ~uint64_t{0};
  uint32_t best_pipe = 0;
  for (uint32_t p = 0; p < count_; ++p) {
    // The first c >= ready with [c, c + interval) clear in pipeline p.
    uint64_t c = ready;
    for (uint64_t k = 0; k < interval_;) {
      if (taken(p, c + k)) {
        c += k + 1;  // no fit starts at or before the taken cycle
        k = 0;
      } else {
        ++k;
      }
    }
    if (c < best) best = c, best_pipe = p;
  }
  for (uint64_t k = 0; k < interval_; ++k) take(best_pipe, best + k);
  return best;
}

void UnitPipelines::grow(uint64_t block) {
  if (block < now_block_) throw std::logic_error("UnitPipelines: an operation ready before the current event");
  size_t words = words_per_pipe_;
  while (block - now_block_ >= words) words *= 2;
  std::vector<Word> ring(count_ * words);
  for (uint32_t p = 0; p < count_; ++p)
    for (size_t i = 0; i < words_per_pipe_; ++i) {
      const Word& w = ring_[size_t{p} * words_per_pipe_ + i];
      if (w.block == Word{}.block || w.block < now_block_) continue;  // empty, or cycles before the current event
      ring[size_t{p} * words + (w.block & (words - 1))] = w;
    }
  ring_.swap(ring);
  words_per_pipe_ = words;
  word_mask_ = words - 1;
}

}  // namespace vbsim::hw
