#include "exact/expectation_block.h"

#include <algorithm>
#include <atomic>

#include "exact/expected_answers.h"
#include "parallel/parallel_for.h"

namespace vbsim {

namespace {

/// Rays a thread takes at a time.
constexpr std::size_t kChunkRays = 64;

}  // namespace

int64_t fill_expect_block(const Oracle& oracle, const Scene& scene, const TraceBlocks& blocks, int threads,
                          std::vector<TraceRay>& rays) {
  rays = blocks.rays();
  std::atomic<int64_t> hits{0};
  parallel_for_chunks(rays.size(), kChunkRays, threads, [&](std::size_t, std::size_t begin, std::size_t end) {
    int64_t chunk_hits = 0;
    for (std::size_t i = begin; i < end; ++i)
      chunk_hits += fill_expect(rays[i], oracle, scene, blocks.parents_for(i)).prim >= 0;
    hits += chunk_hits;
  });
  return hits.load();
}

}  // namespace vbsim
