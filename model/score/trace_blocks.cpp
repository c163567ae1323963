#include "score/trace_blocks.h"

namespace vbsim {

bool TraceBlocks::next_block(size_t max_rays) {
  rays_.clear();
  parent_known_.clear();
  TraceRay tr;
  while ((max_rays == 0 || rays_.size() < max_rays) && source_.next(tr)) {
    parent_known_.push_back(tr.parent >= 0 && parents_.count(tr.parent) != 0);
    parents_[tr.id] = {tr.o, tr.d};
    rays_.push_back(tr);
  }
  return !rays_.empty();
}

}  // namespace vbsim
