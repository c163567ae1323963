// BvhRef: a reference to a BVH subtree, as node child slots and the traversal
// stack hold it (scene/bvh.h).
#pragma once
#include <cstdint>

namespace vbsim {

/// Reference to a subtree: an interior node or a leaf's triangle range.
struct BvhRef {
  uint32_t index = 0;  ///< count 0: index in the tree's nodes; count > 0: first triangle in Bvh::tris
  uint32_t count = 0;  ///< 0: interior node; else the leaf's number of triangles

  bool is_leaf() const { return count != 0; }
};

}  // namespace vbsim
