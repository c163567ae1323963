// Collapsing the binary BVH into a 4- or 8-wide one (Bvh::nodes4 / nodes8), as
// Embree makes its BVH4 and BVH8 from a binary build: from an interior node's
// two children, the interior child of the largest box surface area is replaced
// by its own two children, again and again, until the node holds W children or
// only leaves. Each slot's box and every leaf are the binary tree's own, so a
// search over the wide tree tests the same boxes and triangles, fewer nodes.
// Nodes are in pre-order (a node before its children's subtrees, slot order).
#pragma once
#include "scene/bvh.h"

namespace vbsim {

/// Fills bvh.nodes4 (width 4) or bvh.nodes8 (width 8), bvh.wide_depth and
/// bvh.width from bvh.nodes; width 2 only sets width and wide_depth.
/// std::invalid_argument for another width, or for a tree with nodes of two
/// precisions (their low-precision pool tests binary nodes).
void collapse_bvh(Bvh& bvh, int width);

}  // namespace vbsim
