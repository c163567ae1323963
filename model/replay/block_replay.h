// BlockReplay: the functional replay of a block of trace rays (TraceBlocks:
// each ray with its parent, found in trace order) on several threads. The
// block is cut into chunks of consecutive rays that the threads take in order;
// each chunk counts into statistics of its own and writes its hit lines into a
// buffer of its own, and the chunks are merged in trace order. The statistics
// are integer counts, so their sums are one thread's; the hit lines come out
// in trace order; an error is the one of the earliest ray that failed. Rays
// depend on nothing but their own parent (replay_one_ray), so the answers are
// those of a replay one ray at a time.
#pragma once
#include <array>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "replay/functional_replayer.h"
#include "trace/trace_blocks.h"

namespace vbsim {

class BlockReplay {
 public:
  /// `scene` and `bvh` must outlive it. Throws when the BVH is too deep.
  BlockReplay(const Scene& scene, const Bvh& bvh, const ReplayOptions& options, int threads);

  /// Replays every ray of `blocks`' current block, adding to `stats`, and
  /// writes their hit lines (hit_json_line) to `hits` when it is not null.
  /// Throws what the earliest failing ray threw (before anything is added).
  void replay(const TraceBlocks& blocks, ReplayStats& stats, std::ostream* hits);

 private:
  struct Chunk {
    std::array<KindStats, kRayKindCount> stats;
    std::string hits;  ///< its capacity is kept from block to block
  };
  const Scene& scene_;
  const Bvh& bvh_;
  ReplayOptions opt_;
  CandidateFilter filter_;
  int threads_;
  std::vector<Chunk> chunks_;
};

}  // namespace vbsim
