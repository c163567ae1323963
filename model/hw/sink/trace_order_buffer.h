// TraceOrderBuffer: writes lines that arrive in completion order (the cycle
// model finishes rays out of order) in trace order. A line for trace index i
// is held until the lines of every index before i have been written.
//
// Memory: it holds only the lines finished ahead of the oldest ray still in
// flight, so at most as many as rays finish while one ray is in a slot (a few
// slots' worth in practice), never the whole trace.
#pragma once
#include <cstdint>
#include <deque>
#include <ostream>
#include <string>

namespace vbsim::hw {

class TraceOrderBuffer {
 public:
  /// `out` must outlive the buffer.
  explicit TraceOrderBuffer(std::ostream& out) : out_(out) {}

  /// The line (not empty) of trace index `index` (each index at most once).
  void put(uint64_t index, std::string line) {
    if (index < next_) return;  // already written or skipped: not a valid call
    const uint64_t slot = index - next_;
    if (slot >= held_.size()) held_.resize(slot + 1);
    held_[slot] = std::move(line);
    while (!held_.empty() && !held_.front().empty()) {
      out_ << held_.front();
      held_.pop_front();
      ++next_;
    }
  }

  /// Writes every held line in trace order, skipping the indices that never
  /// came (rays dropped when a run is stopped).
  void flush() {
    for (const std::string& line : held_) out_ << line;
    next_ += held_.size();
    held_.clear();
  }

  size_t held() const { return held_.size(); }  ///< indices held (written or not yet come)
  uint64_t next_index() const { return next_; }  ///< the first index not yet written

 private:
  std::ostream& out_;
  uint64_t next_ = 0;
  std::deque<std::string> held_;  // held_[k]: the line of index next_ + k, empty until it comes
};

}  // namespace vbsim::hw
