// BvhAddressMap: the byte addresses the cycle-level model reads.
//
//   node i          base + i * node_bytes: the nodes of the tree's width (Bvh::width),
//                   64 bytes (BvhNode), 128 (BvhNode4) or 256 (BvhNode8), 64-byte aligned
//   triangle i      tri_base + i * 40, tri_base = base + nodes * node_bytes   (BvhTriangle)
//   spill area      spill_base = tri_base + tris * 40 rounded up to 64; slot s's
//                   traversal stack entry e at spill_base + s * 2048 + e * 16
//                   (128 entries of 16 bytes per slot; see datapath/bvh_stepper.h)
//
// A leaf is one read of count * 40 bytes from its first triangle; a stack refill
// one read of n * 16 bytes.
#pragma once
#include <cstdint>

#include "datapath/closest_hit.h"
#include "scene/bvh.h"

namespace vbsim::hw {

struct BvhAddressMap {
  static constexpr uint32_t kTriangleBytes = 40;
  static constexpr uint32_t kStackEntryBytes = 16;
  static constexpr uint32_t kSpillBytesPerSlot = kTraversalStackDepth * kStackEntryBytes;

  uint32_t node_bytes = 64;
  uint64_t node_base = 0, tri_base = 0, spill_base = 0;

  BvhAddressMap(const Bvh& bvh, uint64_t base)
      : node_bytes(bvh.node_bytes()),
        node_base(base),
        tri_base(base + bvh.traversal_nodes() * uint64_t{node_bytes}),
        spill_base((tri_base + bvh.tris.size() * uint64_t{kTriangleBytes} + 63) / 64 * 64) {}

  uint64_t node(uint32_t i) const { return node_base + uint64_t{i} * node_bytes; }
  uint64_t triangle(uint32_t i) const { return tri_base + uint64_t{i} * kTriangleBytes; }
  uint64_t stack_entry(uint32_t slot, uint32_t entry) const {
    return spill_base + uint64_t{slot} * kSpillBytesPerSlot + uint64_t{entry} * kStackEntryBytes;
  }
};

}  // namespace vbsim::hw
