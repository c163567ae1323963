#include "trace/parent_order_check.h"

#include <fmt/format.h>

namespace vbsim {

std::string ParentOrderProblem::message(const char* position_word) const {
  switch (kind) {
    case Kind::OwnParent:
      return fmt::format("ray {} names itself as its parent", child_id);
    case Kind::ParentLater:
      return fmt::format(
          "child before parent: ray {} names parent {}, which cannot come before it (ids ascend "
          "and {} > {}); a parent must precede its children",
          child_id, parent_id, parent_id, child_id);
    case Kind::ParentArrived:
      return fmt::format(
          "child before parent: ray {} is the parent of ray {} ({} {}), which came before it; a "
          "parent must precede its children",
          parent_id, child_id, position_word, child_position);
    case Kind::None: break;
  }
  return "no problem";
}

ParentOrderCheck::ParentOrderCheck(std::size_t window)
    : window_(window), waiting_capacity_(window) {}

void ParentOrderCheck::compact_waiting_order() {
  std::deque<int64_t> kept;
  for (int64_t parent : waiting_order_)
    if (waiting_.count(parent) != 0) kept.push_back(parent);
  waiting_order_.swap(kept);
}

ParentOrderCheck::Step ParentOrderCheck::add(int64_t id, int64_t parent, int64_t position) {
  Step step;
  ParentOrderProblem& p = step.problem;
  // Is this ray the parent of an earlier child? (Only possible once ids have
  // stopped ascending: a waiting parent id is below the id of its child.)
  if (!waiting_.empty()) {
    const auto it = waiting_.find(id);
    if (it != waiting_.end()) {
      p = {ParentOrderProblem::Kind::ParentArrived, it->second.child_id, it->second.child_position, id};
      waiting_.erase(it);  // its entry in waiting_order_ is skipped when reached
    }
  }
  // Ids still ascend with this ray (trivially for the first one).
  const bool ascending = window_.ascending() && (window_.size() == 0 || id > last_id_);
  if (parent >= 0) {
    step.parent_slot = window_.find(parent);
    if (!p && parent == id) {
      p = {ParentOrderProblem::Kind::OwnParent, id, position, parent};
    } else if (!p && ascending && parent > id) {
      p = {ParentOrderProblem::Kind::ParentLater, id, position, parent};
    } else if (step.parent_slot < 0 && waiting_.find(parent) == waiting_.end()) {
      if (waiting_.size() == waiting_capacity_) {
        while (!waiting_order_.empty() && waiting_.erase(waiting_order_.front()) == 0)
          waiting_order_.pop_front();  // entries already settled
        if (!waiting_order_.empty()) waiting_order_.pop_front();
        ++unchecked_;
      }
      waiting_.emplace(parent, WaitingChild{id, position});
      waiting_order_.push_back(parent);
      if (waiting_order_.size() > 2 * waiting_capacity_) compact_waiting_order();
    }
  }
  step.slot = window_.push(id);
  last_id_ = id;
  return step;
}

}  // namespace vbsim
