// Bvh: the project's compact BVH, built by Embree's rtcBuildBVH (SAH) and laid
// out as the hardware model fetches it from memory.
//
// Layout (little-endian, byte addresses = index * size):
//   BvhNode     32 bytes: bounds lo[3], hi[3] (float32), then
//               offset      interior: index of the second child (the first is this+1)
//                           leaf:     index of the first triangle in `tris`
//               count_axis  bits 0..15: triangle count (0 = interior node),
//                           bits 16..17: split axis of an interior node
//   BvhTriangle 40 bytes: v0, v1, v2 (float32) and prim (scene triangle id)
// Nodes are in depth-first order, root at index 0; triangles in leaf order.
#pragma once
#include <cstdint>
#include <vector>

#include "datapath/triangle.h"
#include "scene/scene.h"

namespace vbsim {

struct BvhNode {
  float lo[3];
  float hi[3];
  uint32_t offset;
  uint32_t count_axis;

  uint32_t count() const { return count_axis & 0xffffu; }
  uint32_t axis() const { return (count_axis >> 16) & 3u; }
  bool is_leaf() const { return count() != 0; }
};
static_assert(sizeof(BvhNode) == 32, "BvhNode is 32 bytes in the hardware layout");

struct BvhTriangle {
  Triangle tri;
  uint32_t prim;
};
static_assert(sizeof(BvhTriangle) == 40, "BvhTriangle is 40 bytes in the hardware layout");

struct BvhBuildOptions {
  int max_leaf_size = 4;  ///< triangles per leaf at most (1..65535)
};

struct Bvh {
  std::vector<BvhNode> nodes;
  std::vector<BvhTriangle> tris;
  int depth = 0;  ///< longest root-to-leaf path, in nodes
};

/// Builds the BVH of `scene` with rtcBuildBVH (SAH, high quality). Every
/// triangle appears in exactly one leaf; an empty scene gives a single empty leaf.
Bvh build_bvh(const Scene& scene, const BvhBuildOptions& options = {});

}  // namespace vbsim
