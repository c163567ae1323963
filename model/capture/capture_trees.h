// The ray trees of a capture and their order in the trace. Each thread's rays
// are linked (ParentLinker) and grouped into trees (a root and every ray
// descended from it, in the thread's call order). The trace lists whole trees,
// sorted by their rays' inputs (op, origin, direction, tmin, tmax, compared as
// floats), so the order does not depend on which thread traced which pixel:
// an application that computes the same rays gives the same trace with any
// number of threads. Parents always precede their children.
#pragma once
#include <cstdint>
#include <vector>

#include "capture/parent_linker.h"
#include "capture/raw_capture_files.h"

namespace vbsim::capture {

struct ThreadRays {
  explicit ThreadRays(MappedRays r) : rays(std::move(r)) {}
  MappedRays rays;
  std::vector<bool> eligible;   ///< belongs to the trace (chosen scene and commit, a valid ray)
  std::vector<RayLink> links;
  std::vector<uint32_t> order;  ///< eligible ray indices, grouped by tree, each tree in call order
};

/// A tree: `count` entries of threads[thread].order from `first`.
struct TreeRef {
  uint32_t thread;
  uint32_t first;
  uint32_t count;
};

/// Fills `t.order` from `t.links` and appends the thread's trees to `trees`.
void group_trees(uint32_t thread_index, ThreadRays& t, std::vector<TreeRef>& trees);

/// Sorts trees into trace order (deterministic; ties are identical trees).
void sort_trees(const std::vector<ThreadRays>& threads, std::vector<TreeRef>& trees);

}  // namespace vbsim::capture
