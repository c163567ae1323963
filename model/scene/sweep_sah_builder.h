// vbsim's own BVH builder: top-down, full-sweep SAH, binary, into the layout of
// bvh.h (the same as Embree's path gives: pre-order nodes, leaves of consecutive
// triangles, exact boxes, child order and axis by bvh_build_common.h).
//
// The triangles' centroids are sorted once on each axis (ties: lower triangle
// id first); a node keeps its triangles in all three orders, and a split
// partitions the other two stably, so no node sorts again. At a node of N
// triangles in a box of area A, every position of each axis's order is a
// candidate split into the first k triangles and the other N - k; its cost, in
// units of one triangle test, is
//     C(axis, k) = traversal_cost + (A_left * B(k) + A_right * B(N - k)) / A
// (A_left, A_right the areas of the two parts' exact boxes; B(n) = ceil(n /
// sah_block_size), the tests n triangles take when a test takes that many at
// once: n itself for sah_block_size 1). The best split is the least C, ties to
// the lower axis, then the lower k. The node is a leaf when
// N <= max_leaf_size and B(N) <= the best C (a leaf of one triangle always);
// otherwise it is split at the best C, or, when that is not below the leaf's N
// (N > max_leaf_size), at the median of the order on the axis of the node box's
// largest extent (ties: lowest axis), the first N / 2 triangles going left. A
// split whose larger part would take the subtree below kMaxSweepSahDepth levels
// (counting the median splits it would need at the least) is replaced by the
// median split, or, for N <= max_leaf_size, by the leaf. Areas and costs are in
// double; the leaf test compares B(N) * A with traversal_cost * A + A_left * B(k) +
// A_right * B(N - k), so a box of area 0 gives leaves (or median splits).
// A leaf lists its triangles in the order of their x centroids.
//
// Deterministic (no threads, every tie broken by index). Time O(N log N) for the
// sorts plus O(N) a level of the tree; memory about 60 bytes a triangle besides
// the Bvh.
#pragma once
#include "scene/bvh.h"

namespace vbsim {

/// The sweep-SAH builder's depth limit, in Bvh::depth's levels (leaf included):
/// within the traversal stack (kTraversalStackDepth 128, closest_hit.h).
constexpr int kMaxSweepSahDepth = 64;

/// Builds the BVH of `scene` as above with `options.max_leaf_size`,
/// `options.traversal_cost` and `options.sah_block_size` (checked by build_bvh, which calls this for
/// BvhBuilder::SweepSah; `options.quality` is not used). Throws SceneError for a
/// non-finite vertex. An empty scene gives Bvh's empty tree.
Bvh build_sweep_sah_bvh(const Scene& scene, const BvhBuildOptions& options);

}  // namespace vbsim
