// TraceBlocks: reads a trace in blocks of rays, so that several configurations
// can replay the same rays from one parse, or several threads can share the
// rays of one block (replay, oracle). Each ray's parent (o, d) is looked
// up when the ray is read, in a ParentRayStore of the last `parent_window`
// rays, and kept beside the ray: a ray sees its parent only when the parent
// came before it in the trace, as in a streamed replay, and memory stays
// bounded by the block and the window, whatever the trace's length.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "trace/parent_ray_store.h"
#include "trace/trace_record.h"
#include "trace/trace_source.h"

namespace vbsim {

class TraceBlocks {
 public:
  explicit TraceBlocks(TraceSource& source, int64_t parent_window = ParentRayStore::kDefaultWindow)
      : source_(source), parents_(parent_window) {}

  /// Reads up to `max_rays` further rays (all when 0) into rays(); false when
  /// none were left. Throws TraceError from the reader, and a TraceError at the
  /// ray (field 'parent') whose parent lies beyond the parent window. When it
  /// throws, rays() and parents_for() hold the block's rays before the one at
  /// fault, so that a caller can finish them first and report errors in trace
  /// order.
  bool next_block(size_t max_rays);
  const std::vector<TraceRay>& rays() const { return rays_; }
  /// The parent ray of ray `i` of the block when it came before it, else null.
  const ParentRay* parents_for(size_t i) const { return parent_known_[i] ? &parent_[i] : nullptr; }
  /// Rays read so far, over every block.
  int64_t rays_read() const { return rays_read_; }

 private:
  TraceSource& source_;
  std::vector<TraceRay> rays_;
  std::vector<ParentRay> parent_;
  std::vector<uint8_t> parent_known_;
  ParentRayStore parents_;
  int64_t rays_read_ = 0;
};

}  // namespace vbsim
