// UnitPipelines: the `count` identical pipelines of one kind in one core (box
// tests, triangle tests or the avoidance unit), as a reservation table. An
// operation whose operands are ready at cycle r issues at the earliest cycle
// c >= r at which one of the pipelines can accept it - a pipeline accepts a new
// operation `issue_interval` cycles after its previous one, so an operation
// issued at c holds its pipeline's issue cycles [c, c + issue_interval) - and
// has its result `latency` cycles later. Of the pipelines free at c the lowest
// numbered takes it.
//
// Operations are reserved when the step that needs them is handled (in time
// order of the steps), usually for a cycle ahead of it, and an operation takes
// any free issue cycle at or after its ready cycle, also one before cycles that
// earlier requests reserved: a box test waiting for a node from DRAM does not
// hold back one whose node arrives earlier (the unit takes whatever operation is
// ready, as an issue queue in front of it would). Between operations ready at
// the same cycle the one requested first wins.
//
// Each pipeline keeps a bit per cycle (set: an issue cycle taken) in a ring of
// 64-cycle words, each word tagged with the block of 64 cycles it holds now: a
// word whose tag is an earlier block holds only cycles before the current event,
// which are never asked for again, so it reads as empty and is reused without
// being cleared. The ring spans at least the cycles from the current event's
// block on that reservations can reach; it grows when one falls beyond it.
// Operations and their waits are added to a UnitCounters the caller owns (the
// engine sums every core's pipelines of one kind into one).
#pragma once
#include <cstdint>
#include <vector>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"

namespace vbsim::hw {

class UnitPipelines {
 public:
  /// `totals` must outlive the pipelines. count >= 1, issue_interval >= 1 (the
  /// configuration is validated).
  UnitPipelines(const UnitConfig& c, UnitCounters& totals);

  /// Issue cycle of an operation whose operands are ready at `ready`, requested
  /// while handling the event at cycle `now`: `now` never decreases from one
  /// call to the next, and ready >= now.
  uint64_t issue(uint64_t ready, uint64_t now) {
    now_block_ = now / kWordBits;
    const uint64_t at = count_ == 1 && interval_ == 1 ? issue_single(ready) : issue_general(ready);
    ++totals_->ops;
    totals_->wait_cycles += at - ready;
    return at;
  }
  uint32_t latency() const { return latency_; }

 private:
  static constexpr uint32_t kWordBits = 64;

  /// One pipeline accepting an operation every cycle: the first clear bit at or after `ready`.
  uint64_t issue_single(uint64_t ready) {
    for (uint64_t from = ready;; from = (from / kWordBits + 1) * kWordBits) {  // then the next word's first cycle
      const uint64_t block = from / kWordBits;
      Word& w = word(0, block);
      const uint64_t bits = w.bits & current_mask(w.block, block);
      const uint64_t free_bits = ~bits >> (from % kWordBits);  // bit k: cycle from + k is free
      if (free_bits == 0) continue;                             // the rest of the word is taken
      const uint64_t at = from + static_cast<uint64_t>(__builtin_ctzll(free_bits));
      w.bits = bits | uint64_t{1} << (at % kWordBits);
      w.block = block;
      return at;
    }
  }
  uint64_t issue_general(uint64_t ready);

  /// The 64 cycles of one block in one pipeline: a bit per cycle (set: taken),
  /// valid while `block` is the block they belong to.
  struct Word {
    uint64_t bits = 0, block = ~uint64_t{0};
  };
  /// Pipeline `pipe`'s word for `block` (the ring spans it: grown when needed).
  Word& word(uint32_t pipe, uint64_t block) {
    if (block - now_block_ >= words_per_pipe_) grow(block);
    return ring_[size_t{pipe} * words_per_pipe_ + (block & word_mask_)];
  }
  /// All ones when a word tagged `tag` holds `block`, else 0 (no branch: whether
  /// a block was written before is as good as random to the host).
  static uint64_t current_mask(uint64_t tag, uint64_t block) { return uint64_t{0} - uint64_t{tag == block}; }
  bool taken(uint32_t pipe, uint64_t cycle) {
    const uint64_t block = cycle / kWordBits;
    const Word& w = word(pipe, block);
    return ((w.bits & current_mask(w.block, block)) >> (cycle % kWordBits)) & 1u;
  }
  void take(uint32_t pipe, uint64_t cycle) {
    const uint64_t block = cycle / kWordBits;
    Word& w = word(pipe, block);
    w.bits = (w.bits & current_mask(w.block, block)) | uint64_t{1} << (cycle % kWordBits);
    w.block = block;
  }
  /// Makes the ring span blocks now_block_ .. `block` (it holds no block before now_block_ that matters).
  void grow(uint64_t block);

  uint32_t count_, latency_, interval_;
  size_t words_per_pipe_;  // a power of two
  uint64_t word_mask_;     // words_per_pipe_ - 1
  uint64_t now_block_ = 0;  // the current event's block of 64 cycles
  std::vector<Word> ring_;  // count_ rings of words_per_pipe_ words
  UnitCounters* totals_;
};

}  // namespace vbsim::hw
