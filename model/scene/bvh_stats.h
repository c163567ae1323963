// BvhStats: shape and memory figures of a built Bvh, for the docs and the
// hardware model's memory sizing.
#pragma once
#include <cstdint>
#include <string>

#include "scene/bvh.h"

namespace vbsim {

/// Cost constants of the SAH figure; equal to the traversal and intersection
/// costs build_bvh passes to Embree by default (BvhBuildOptions::traversal_cost 1).
constexpr double kSahTraversalCost = 1.0;
constexpr double kSahIntersectionCost = 1.0;

struct BvhStats {
  int64_t nodes = 0;            ///< BvhNode records: interior nodes (leaves have none)
  int64_t leaves = 0;           ///< leaves (a root leaf counts; an empty scene has none)
  int64_t triangles = 0;        ///< entries of Bvh::tris
  double average_leaf_size = 0; ///< triangles per leaf
  int64_t max_leaf_size = 0;    ///< triangles in the largest leaf
  int depth = 0;                ///< levels on the longest root-to-leaf path, leaf included (Bvh::depth), recounted
  int64_t node_bytes = 0;       ///< nodes * sizeof(BvhNode)
  int width = 2;                ///< children per node traversal reads (Bvh::width)
  int64_t wide_nodes = 0;       ///< width 4 or 8: the wide tree's nodes (traversal reads them); 2: nodes
  int64_t wide_node_bytes = 0;  ///< wide_nodes * 128 (width 4) or 256 (width 8); 2: node_bytes
  int wide_depth = 0;           ///< the wide tree's levels, leaf included (Bvh::wide_depth); 2: depth
  int64_t triangle_bytes = 0;   ///< triangles * sizeof(BvhTriangle)
  /// Expected cost of a ray that enters the root, in units of one node visit:
  /// sum over interior nodes of kSahTraversalCost * A(n) / A(root) plus sum over
  /// leaves of kSahIntersectionCost * count * A(n) / A(root), A = surface area
  /// (double) of the subtree's box (its parent's child slot, or root_bounds).
  /// A root of zero area weighs every subtree 1.
  double sah_cost = 0;
};

/// Walks `bvh` from the root (precondition: a tree as build_bvh makes it).
BvhStats compute_bvh_stats(const Bvh& bvh);

/// One figure per line, "name: value unit", for logs and docs.
std::string format_bvh_stats(const BvhStats& stats);

}  // namespace vbsim
