#include "replay/block_replay.h"

#include <algorithm>

#include "parallel/parallel_for.h"
#include "replay/replay_run.h"

namespace vbsim {

namespace {

/// Rays a thread takes at a time.
constexpr std::size_t kChunkRays = 128;

}  // namespace

BlockReplay::BlockReplay(const Scene& scene, const Bvh& bvh, const ReplayOptions& options, int threads)
    : scene_(scene),
      bvh_(bvh),
      opt_(options),
      filter_(options.method, scene.mask_table()),
      threads_(std::max(threads, 1)) {
  check_traversal_depth(bvh);
}

void BlockReplay::replay(const TraceBlocks& blocks, ReplayStats& stats, std::ostream* hits) {
  const std::vector<TraceRay>& rays = blocks.rays();
  const std::size_t chunks = chunk_count(rays.size(), kChunkRays);
  if (chunks_.size() < chunks) chunks_.resize(chunks);
  parallel_for_chunks(rays.size(), kChunkRays, threads_, [&](std::size_t c, std::size_t begin, std::size_t end) {
    Chunk& chunk = chunks_[c];
    chunk.stats = {};
    chunk.hits.clear();
    for (std::size_t i = begin; i < end; ++i) {
      const TraceRay& tr = rays[i];
      const RayOutcome out = replay_one_ray(tr, scene_, bvh_, opt_, filter_, blocks.parents_for(i),
                                            chunk.stats[static_cast<int>(tr.kind)]);
      if (hits) append_hit_json_line(chunk.hits, tr, out);
    }
  });
  for (std::size_t c = 0; c < chunks; ++c) {
    for (int k = 0; k < kRayKindCount; ++k) stats.by_kind[k].add(chunks_[c].stats[k]);
    if (hits) hits->write(chunks_[c].hits.data(), static_cast<std::streamsize>(chunks_[c].hits.size()));
  }
}

}  // namespace vbsim
