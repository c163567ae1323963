// WideBvhNode<W>: an interior node of a W-wide BVH (W = 4 or 8, as RDNA's and
// Embree's BVH4/BVH8), laid out as a hardware BVH unit fetches it: one fetch
// gives the boxes and references of all W child slots, and one box-unit
// operation tests them all.
//
// Layout (little-endian, byte address = index * sizeof, nodes 64-byte aligned):
//   bytes 0 .. 24W-1   box[3][2][W] float32: box[axis][side][slot], side 0 = low
//                      bound, 1 = high; so a ray's near (or far) bounds on one
//                      axis for every slot are W consecutive floats
//   then  4W bytes     ref[W]   uint32 per slot (BvhRef::index)
//   then  2W bytes     count[W] uint16 per slot (BvhRef::count: 0 interior)
//   then  4 bytes      children uint32: slots in use, 2..W, the first ones
//   then  padding to 128 bytes (W 4) or 256 bytes (W 8)
// An unused slot holds an inverted box (low +inf, high -inf), which no ray
// meets, and reference {0, 0}. The functional search's vector box tests rely
// on that (they do not mask slots >= children); the scalar form and the
// timing model's box unit mask them as well.
// Slots are in the order a depth-first walk of the binary tree they were
// collapsed from meets the subtrees (scene/bvh_collapse.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>

#include "scene/bvh_ref.h"
#include "scene/scene.h"

namespace vbsim {

template <int W>
struct alignas(64) WideBvhNode {
  static_assert(W == 4 || W == 8, "wide nodes are 4 or 8 wide");
  static constexpr int kWidth = W;

  float box[3][2][W];  ///< box[axis][0 low | 1 high][slot]
  uint32_t ref[W];
  uint16_t count[W];
  uint32_t children;   ///< slots in use (the first ones)

  BvhRef child(int c) const { return slot_ref(*this, c); }
  Bounds3f child_bounds(int c) const { return slot_bounds(*this, c); }
  void set_child(int c, const Bounds3f& b, BvhRef r) { set_slot(*this, c, b, r); }
  /// Every slot unused: inverted boxes, null references, no children.
  void clear() {
    constexpr float inf = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < W; ++c) {
        box[a][0][c] = inf;
        box[a][1][c] = -inf;
      }
    for (int c = 0; c < W; ++c) {
      ref[c] = 0;
      count[c] = 0;
    }
    children = 0;
  }
};

using BvhNode4 = WideBvhNode<4>;
using BvhNode8 = WideBvhNode<8>;
static_assert(sizeof(BvhNode4) == 128 && offsetof(BvhNode4, ref) == 96 && offsetof(BvhNode4, count) == 112 &&
                  offsetof(BvhNode4, children) == 120,
              "BvhNode4 is 128 bytes in the hardware layout");
static_assert(sizeof(BvhNode8) == 256 && offsetof(BvhNode8, ref) == 192 && offsetof(BvhNode8, count) == 224 &&
                  offsetof(BvhNode8, children) == 240,
              "BvhNode8 is 256 bytes in the hardware layout");

}  // namespace vbsim
