// ParentOrderCheck: the trace rule "a parent precedes its children", checked
// over a stream of rays in trace order in bounded memory (the rule and what
// is decidable: docs/trace-format.md, "Consistency checks").
//
// Contract, for a caller that sees rays one at a time (the trace readers'
// consumers, the cycle model's feed):
// - add(id, parent, position) once per ray, in trace order; ids are unique
//   (the readers reject duplicates). `position` is the caller's locator of the
//   ray (a text line, a binary record index), echoed back in a problem.
// - It reports a ray that names itself as parent, and, while the trace's ids
//   ascend (every id greater than the one before, as every vbsim writer and
//   the capture produce), a ray whose parent id is greater than its own: that
//   parent comes later or never. Both are decided at the child, exactly.
// - A parent not among the last `window` rays is remembered for up to
//   `window` such children; when a later ray turns out to be that parent, the
//   problem is reported at the parent and names the earliest such child.
//   Children dropped from that list are counted in unchecked(); a parent that
//   never appears is allowed (a trace may hold part of a render).
// Memory: O(window), never O(trace).
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <unordered_map>

#include "trace/parent_window.h"
#include "trace/recent_id_window.h"

namespace vbsim {

struct ParentOrderProblem {
  enum class Kind : uint8_t {
    None,
    OwnParent,     ///< parent == id
    ParentLater,   ///< ids ascend and parent > id: found at the child
    ParentArrived  ///< a ray arrived that an earlier ray named as parent: found at the parent
  };
  Kind kind = Kind::None;
  int64_t child_id = -1;
  int64_t child_position = -1;  ///< the caller's locator of the child
  int64_t parent_id = -1;

  explicit operator bool() const { return kind != Kind::None; }
  /// One sentence; `position_word` names the caller's locator ("line", "record").
  std::string message(const char* position_word) const;
};

class ParentOrderCheck {
 public:
  /// The replays' parent window (trace/parent_window.h): one window for both.
  static constexpr std::size_t kDefaultWindow = static_cast<std::size_t>(kDefaultParentWindow);

  explicit ParentOrderCheck(std::size_t window = kDefaultWindow);

  /// The outcome of add(): a problem (or none) and where the rays sit in the window.
  struct Step {
    ParentOrderProblem problem;
    std::size_t slot = 0;      ///< this ray's slot in window()
    int64_t parent_slot = -1;  ///< the parent's slot, -1 when it is not in the window
  };
  /// Feeds the next ray of the trace (parent -1 for a camera ray).
  Step add(int64_t id, int64_t parent, int64_t position);

  /// The ids of the last `window` rays; slots index a caller's parallel data.
  const RecentIdWindow& window() const { return window_; }
  /// Children whose parent was neither in the window nor seen before they
  /// were dropped from the waiting list: their order could not be checked.
  int64_t unchecked() const { return unchecked_; }

 private:
  struct WaitingChild {
    int64_t child_id;
    int64_t child_position;
  };
  /// Drops the ids of settled parents from waiting_order_ (which keeps it O(window)).
  void compact_waiting_order();

  RecentIdWindow window_;
  int64_t last_id_ = -1;
  std::size_t waiting_capacity_;
  std::unordered_map<int64_t, WaitingChild> waiting_;  ///< missing parent id -> first child naming it
  std::deque<int64_t> waiting_order_;                   ///< parent ids in the order they were added
  int64_t unchecked_ = 0;
};

}  // namespace vbsim
