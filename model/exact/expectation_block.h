// The oracle over a block of trace rays on several threads: each ray's exact
// answer depends on nothing but the ray, its parent (found in trace order by
// TraceBlocks) and the scene, so the rays of a block are answered in any order
// and written in trace order, as ExpectationFiller answers them one at a time.
#pragma once
#include <cstdint>
#include <vector>

#include "exact/oracle.h"
#include "trace/trace_blocks.h"

namespace vbsim {

/// Sets expect (as ExpectationFiller::fill does) on the rays of `blocks`'
/// current block, copied into `rays` in trace order, on up to `threads`
/// threads; returns how many hit a triangle. Throws what the earliest failing
/// ray threw.
int64_t fill_expect_block(const Oracle& oracle, const Scene& scene, const TraceBlocks& blocks, int threads,
                          std::vector<TraceRay>& rays);

}  // namespace vbsim
