// BvhRef: a reference to a BVH subtree, as node child slots and the traversal
// stack hold it (scene/bvh.h).
#pragma once
#include <cstdint>

#include "scene/scene.h"

namespace vbsim {

/// Reference to a subtree: an interior node or a leaf's triangle range.
struct BvhRef {
  uint32_t index = 0;  ///< count 0: index in the tree's nodes; count > 0: first triangle in Bvh::tris
  uint32_t count = 0;  ///< 0: interior node; else the leaf's number of triangles

  bool is_leaf() const { return count != 0; }
};

/// The child slots every node layout shares: `box[axis][0 low | 1 high][slot]`
/// float32 bounds and per-slot `ref` / `count` (bvh.h's BvhNode, wide_bvh_node.h's
/// WideBvhNode). What slot `c` refers to, its box, and storing both.
template <class Node>
BvhRef slot_ref(const Node& n, int c) {
  return {n.ref[c], n.count[c]};
}
template <class Node>
Bounds3f slot_bounds(const Node& n, int c) {
  Bounds3f b;
  b.lo = {n.box[0][0][c], n.box[1][0][c], n.box[2][0][c]};
  b.hi = {n.box[0][1][c], n.box[1][1][c], n.box[2][1][c]};
  return b;
}
/// Precondition: r.count <= 65535.
template <class Node>
void set_slot(Node& n, int c, const Bounds3f& b, BvhRef r) {
  for (int a = 0; a < 3; ++a) {
    n.box[a][0][c] = b.lo[a];
    n.box[a][1][c] = b.hi[a];
  }
  n.ref[c] = r.index;
  n.count[c] = static_cast<uint16_t>(r.count);
}

}  // namespace vbsim
