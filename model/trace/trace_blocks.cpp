#include "trace/trace_blocks.h"

namespace vbsim {

bool TraceBlocks::next_block(size_t max_rays) {
  rays_.clear();
  parent_.clear();
  parent_known_.clear();
  TraceRay tr;
  while ((max_rays == 0 || rays_.size() < max_rays) && source_.next(tr)) {
    const ParentRay* parent = nullptr;
    try {
      parent = parents_.lookup(tr.parent);
    } catch (const ParentWindowError& e) {
      throw source_.error_at_last_ray("parent", e.what());
    }
    parent_known_.push_back(parent != nullptr);
    parent_.push_back(parent ? *parent : ParentRay{});
    parents_.add(tr.id, tr.o, tr.d);
    rays_.push_back(tr);
    ++rays_read_;
  }
  return !rays_.empty();
}

}  // namespace vbsim
