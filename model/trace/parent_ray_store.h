// ParentRayStore: the parent rays a streamed pass over a trace can still look
// up, in bounded memory. A child ray names its parent by id; the intended
// origin (trace spec, "The exact answer") and the ray-equation hit point need
// that parent's o and d. The store keeps the `window` rays added last and
// nothing else, so its memory does not grow with the trace.
//
// Contract:
//   - add(id, ...) records a ray in trace order; when `window` rays are held,
//     the oldest is dropped first (FIFO by add order, not by id). Adding an id
//     that is held replaces its o and d in place.
//   - lookup(id) gives the parent when it is held; nullptr when it was never
//     added (a parent not in the trace, or one that comes after the child:
//     the spec then falls back to parent_uv); and throws ParentWindowError when
//     it was added and dropped, so that a trace whose parents lie beyond the
//     window is refused, never replayed with a different meaning.
//   - Memory: at most `window` entries of 32 bytes plus a 4-byte index slot per
//     entry at a load of at most 1/2, about 40 bytes a ray (5.2 MB for the
//     default window), allocated as rays arrive. The record of dropped ids
//     (trace_id_set.h) keeps ranges of consecutive ids, at most as many as
//     the window has rays (at least 1024; about 64 bytes a range), whatever
//     the trace's length or the order of its ids. Ids in trace order are one
//     range. Past that many ranges the lowest ones merge, and a child whose
//     parent id falls in a merged range and is not held is refused with
//     ParentWindowError (whether that parent came earlier is no longer known),
//     never replayed as if its parent had never come.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "datapath/vec3.h"
#include "trace/parent_window.h"
#include "trace/trace_id_set.h"
#include "trace/trace_validation.h"

namespace vbsim {

/// What a child needs of its parent ray: its origin and direction as the trace gives them.
struct ParentRay {
  Vec3f o, d;
};

/// A child names a parent that the store held and dropped: the parent lies
/// more than the window's rays before it. what(): the message without location
/// (the caller adds file and line or record).
struct ParentWindowError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class ParentRayStore {
 public:
  /// Default window: a child's parent must be among the 131072 rays added
  /// before it (trace/parent_window.h: the consistency checks use the same).
  static constexpr int64_t kDefaultWindow = kDefaultParentWindow;
  /// Largest window (2^31 - 1 rays, about 80 GB): slot indices are 32-bit.
  static constexpr int64_t kMaxWindow = kMaxParentWindow;

  /// Throws std::invalid_argument unless 1 <= window <= kMaxWindow.
  explicit ParentRayStore(int64_t window = kDefaultWindow);

  /// Records ray `id` (>= 0) with origin `o` and direction `d`.
  void add(int64_t id, Vec3f o, Vec3f d);
  /// The ray `id` when held, else nullptr; throws ParentWindowError when `id`
  /// was added and has been dropped. Valid until the next add().
  const ParentRay* lookup(int64_t id) const;

  int64_t window() const { return window_; }
  /// True while the record of dropped ids is exact (no ranges merged): lookup
  /// then never throws for an id that was never added.
  bool dropped_ids_exact() const { return dropped_.exact(); }
  /// Rays held now (at most window()).
  int64_t size() const { return static_cast<int64_t>(held_); }

 private:
  struct Entry {
    int64_t id;
    ParentRay ray;
  };
  /// Index slot of `id` in table_: where it is, or the empty slot where it would go.
  size_t find_slot(int64_t id) const;
  void erase_slot(size_t slot);
  void grow_table();

  int64_t window_;
  std::vector<Entry> ring_;      ///< add order, wrapping at window_ once full
  size_t oldest_ = 0;            ///< ring_ index of the oldest entry once the ring is full
  size_t held_ = 0;
  std::vector<uint32_t> table_;  ///< open addressing: ring index + 1, 0 = empty; size a power of two
  TraceIdSet dropped_;           ///< ids added and dropped
};

/// The rays of a trace held in memory whole (generators, tests): id -> ray.
using ParentRays = std::unordered_map<int64_t, ParentRay>;

/// `parents[id]` when present, else nullptr.
inline const ParentRay* find_parent(const ParentRays& parents, int64_t id) {
  const auto it = parents.find(id);
  return it == parents.end() ? nullptr : &it->second;
}

/// The message of a ParentWindowError for a child naming `parent`.
std::string parent_window_message(int64_t parent, int64_t window);

}  // namespace vbsim
