// TraceBlocks: reads a trace in blocks of rays so that several configurations
// can replay the same rays from one parse, and keeps the parent rays (o, d of
// every ray read) that replay_one_ray looks up. A ray sees its parent only when
// the parent came before it in the trace, as in a streamed replay.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "trace/parent_rays.h"
#include "trace/trace_record.h"
#include "trace/trace_source.h"

namespace vbsim {

class TraceBlocks {
 public:
  explicit TraceBlocks(TraceSource& source) : source_(source) {}

  /// Reads up to `max_rays` further rays (all when 0) into rays(); false when
  /// none were left. Throws TraceError from the reader.
  bool next_block(size_t max_rays);
  const std::vector<TraceRay>& rays() const { return rays_; }
  /// The parent rays for ray `i` of the block: the map when the ray's parent
  /// came before it, else null (no parent data).
  const ParentRays* parents_for(size_t i) const { return parent_known_[i] ? &parents_ : nullptr; }

 private:
  TraceSource& source_;
  std::vector<TraceRay> rays_;
  std::vector<uint8_t> parent_known_;
  ParentRays parents_;
};

}  // namespace vbsim
