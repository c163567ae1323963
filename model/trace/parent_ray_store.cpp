#include "trace/parent_ray_store.h"

#include <fmt/format.h>

#include <algorithm>

namespace vbsim {

namespace {

constexpr size_t kInitialTableSlots = 1024;

/// splitmix64's finaliser: ids that are trace positions spread over the table.
uint64_t mix(int64_t id) {
  uint64_t z = static_cast<uint64_t>(id) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

}  // namespace

std::string parent_window_message(int64_t parent, int64_t window) {
  return fmt::format("parent {} lies more than {} rays before this ray (the parent window); a replay keeps "
                     "only that many rays to look parents up in: raise it with --parent-window",
                     parent, window);
}

std::string parent_unknown_message(int64_t parent, int64_t window, std::size_t ranges) {
  return fmt::format("parent {} is not among the last {} rays (the parent window), and this trace's ids run in "
                     "so many separate ranges (more than {}) that whether it came earlier is no longer known; "
                     "renumber the trace's ids in trace order, or raise --parent-window",
                     parent, window, ranges);
}

/// The record of dropped ids keeps as many ranges as the window has rays (at
/// least 1024): its memory follows the window, never the trace.
std::size_t dropped_ranges(int64_t window) { return static_cast<std::size_t>(std::max<int64_t>(window, 1024)); }

ParentRayStore::ParentRayStore(int64_t window) : window_(window), dropped_(dropped_ranges(window)) {
  if (window < 1 || window > kMaxWindow)
    throw std::invalid_argument(fmt::format("parent window {} is not in 1..{}", window, kMaxWindow));
  table_.assign(kInitialTableSlots, 0);
}

size_t ParentRayStore::find_slot(int64_t id) const {
  const size_t mask = table_.size() - 1;
  size_t slot = mix(id) & mask;
  while (table_[slot] != 0 && ring_[table_[slot] - 1].id != id) slot = (slot + 1) & mask;
  return slot;
}

// Backward-shift deletion keeps every probe chain unbroken without tombstones.
void ParentRayStore::erase_slot(size_t slot) {
  const size_t mask = table_.size() - 1;
  size_t hole = slot;
  for (size_t next = (hole + 1) & mask; table_[next] != 0; next = (next + 1) & mask) {
    const size_t home = mix(ring_[table_[next] - 1].id) & mask;
    // The entry at `next` may move into the hole when its home is not in (hole, next].
    const bool stays = hole <= next ? (hole < home && home <= next) : (hole < home || home <= next);
    if (!stays) {
      table_[hole] = table_[next];
      hole = next;
    }
  }
  table_[hole] = 0;
}

void ParentRayStore::grow_table() {
  std::vector<uint32_t> old;
  old.swap(table_);
  table_.assign(old.size() * 2, 0);
  for (uint32_t index : old)
    if (index != 0) table_[find_slot(ring_[index - 1].id)] = index;
}

void ParentRayStore::add(int64_t id, Vec3f o, Vec3f d) {
  const size_t slot = find_slot(id);
  if (table_[slot] != 0) {  // held: replace in place
    ring_[table_[slot] - 1].ray = {o, d};
    return;
  }
  size_t index;
  if (held_ < static_cast<size_t>(window_)) {
    if (ring_.size() == ring_.capacity())  // grow by doubling, never past the window
      ring_.reserve(std::min<size_t>(static_cast<size_t>(window_), std::max<size_t>(64, 2 * ring_.size())));
    ring_.push_back({id, {o, d}});
    index = ring_.size() - 1;
    ++held_;
  } else {  // full: the oldest entry makes room
    index = oldest_;
    const int64_t dropped = ring_[index].id;
    erase_slot(find_slot(dropped));
    dropped_.insert(dropped);
    ring_[index] = {id, {o, d}};
    oldest_ = (oldest_ + 1) % static_cast<size_t>(window_);
  }
  // Keep the load at most 1/2 (the table stops growing with the ring).
  if (2 * held_ > table_.size()) grow_table();
  table_[find_slot(id)] = static_cast<uint32_t>(index + 1);
}

const ParentRay* ParentRayStore::lookup(int64_t id) const {
  const uint32_t index = table_[find_slot(id)];
  if (index != 0) return &ring_[index - 1].ray;
  if (id < 0) return nullptr;
  switch (dropped_.contains(id)) {
    case TraceIdSet::Membership::Yes:
      throw ParentWindowError(parent_window_message(id, window_));
    case TraceIdSet::Membership::Unknown:  // never replayed with another meaning: refused
      throw ParentWindowError(parent_unknown_message(id, window_, dropped_.max_ranges()));
    case TraceIdSet::Membership::No:
      break;
  }
  return nullptr;
}

}  // namespace vbsim
