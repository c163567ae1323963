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
// 64-cycle words: the word at position (block mod ring size) holds block
// `block` of 64 cycles, for the blocks from the current event's on. When the
// current event moves past a block its word is cleared, ready for the block
// one ring further on (cycles before the current event are never asked for
// again). The ring grows when a reservation falls beyond it.
// Operations and their waits are added to a UnitCounters the caller owns (the
// engine sums every core's pipelines of one kind into one).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"

namespace vbsim::hw {

class UnitPipelines {
 public:
  /// `totals` must outlive the pipelines. count >= 1, issue_interval >= 1 (the
  /// configuration is validated). `owner` names the unit in errors.
  UnitPipelines(const UnitConfig& c, UnitCounters& totals, std::string owner = "UnitPipelines");

  /// Issue cycle of an operation whose operands are ready at `ready`, requested
  /// while handling the event at cycle `now`: `now` never decreases from one
  /// call to the next, and ready >= now.
  uint64_t issue(uint64_t ready, uint64_t now) { return reserve(ready, now, interval_); }
  /// The same for an operation that holds its pipeline `interval` (>= 1) cycles
  /// instead of the configured issue interval (a controller's step of a kind
  /// with its own, hw.controller.by_step); these are counted in busy_cycles.
  uint64_t issue(uint64_t ready, uint64_t now, uint32_t interval) {
    totals_->busy_cycles += interval;
    return reserve(ready, now, interval);
  }
  uint32_t latency() const { return latency_; }

 private:
  static constexpr uint32_t kWordBits = 64;

  /// One pipeline accepting an operation every cycle: the first clear bit at or after `ready`.
  uint64_t issue_single(uint64_t ready) {
    for (uint64_t from = ready;; from = (from / kWordBits + 1) * kWordBits) {  // then the next word's first cycle
      uint64_t& w = word(0, from / kWordBits);
      const uint64_t free_bits = ~w >> (from % kWordBits);  // bit k: cycle from + k is free
      if (free_bits == 0) continue;                          // the rest of the word is taken
      const uint64_t at = from + static_cast<uint64_t>(__builtin_ctzll(free_bits));
      w |= uint64_t{1} << (at % kWordBits);
      return at;
    }
  }
  uint64_t issue_general(uint64_t ready, uint32_t interval);

  /// An operation holding its pipeline `interval` cycles: its issue cycle, counted.
  __attribute__((always_inline)) uint64_t reserve(uint64_t ready, uint64_t now, uint32_t interval) {
    if (now / kWordBits != now_block_) move_to(now / kWordBits);
    const uint64_t at = count_ == 1 && interval == 1 ? issue_single(ready) : issue_general(ready, interval);
    ++totals_->ops;
    totals_->wait_cycles += at - ready;
    return at;
  }

  /// Pipeline `pipe`'s word for `block`, a block from the current one on (the
  /// ring spans it: grown when needed).
  uint64_t& word(uint32_t pipe, uint64_t block) {
    if (block - now_block_ >= words_per_pipe_) grow(block);
    return ring_[size_t{pipe} * words_per_pipe_ + (block & word_mask_)];
  }
  bool taken(uint32_t pipe, uint64_t cycle) { return (word(pipe, cycle / kWordBits) >> (cycle % kWordBits)) & 1u; }
  void take(uint32_t pipe, uint64_t cycle) { word(pipe, cycle / kWordBits) |= uint64_t{1} << (cycle % kWordBits); }
  /// The current event is in block `block` (> now_block_): clears the words of
  /// the blocks it left.
  void move_to(uint64_t block);
  /// Makes the ring span blocks now_block_ .. `block` (it holds no block before now_block_ that matters).
  void grow(uint64_t block);

  uint32_t count_, latency_, interval_;
  size_t words_per_pipe_;  // a power of two
  uint64_t word_mask_;     // words_per_pipe_ - 1
  uint64_t now_block_ = 0;  // the current event's block of 64 cycles
  std::vector<uint64_t> ring_;  // count_ rings of words_per_pipe_ words
  UnitCounters* totals_;
  std::string owner_;
};

}  // namespace vbsim::hw
