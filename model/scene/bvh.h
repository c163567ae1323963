// Bvh: the project's compact binary BVH, built by Embree's rtcBuildBVH (SAH)
// or by vbsim's own full-sweep SAH builder (sweep_sah_builder.h), and laid out as a hardware BVH unit fetches it: one 64-byte node fetch gives
// the boxes and references of BOTH children, so an interior node's two box
// tests need no further fetch.
//
// Layout (little-endian, byte address = index * size, nodes 64-byte aligned):
//   BvhNode 64 bytes, one per INTERIOR node; leaves are no records of their own.
//     bytes  0..47  box[3][2][2] float32: box[axis][side][child], side 0 = low
//                   bound, 1 = high bound. In memory (SoA): lo_x[2], hi_x[2],
//                   lo_y[2], hi_y[2], lo_z[2], hi_z[2], where lo_x[c] is child
//                   c's low x bound; so a ray's near (or far) bounds on one axis
//                   for both children are one 8-byte pair.
//     bytes 48..55  ref[2]   uint32 per child: count 0 -> index in `nodes` of the
//                            child's node; count > 0 -> index in `tris` of the
//                            leaf's first triangle
//     bytes 56..59  count[2] uint16 per child: 0 = interior child, 1..65535 = a
//                            leaf of that many consecutive triangles of `tris`
//     bytes 60..63  axis     uint32: split axis (0 x, 1 y, 2 z); child 0's box
//                            centre is not above child 1's on it
//   BvhTriangle 40 bytes: v0, v1, v2 (float32) and prim (scene triangle id)
//
// The root is described in Bvh like a child slot: its box `root_bounds` and its
// reference `root` (BvhRef, same encoding as ref/count). When the whole tree is
// one leaf (1..max_leaf_size triangles) `root` is that leaf and `nodes` is
// empty; otherwise `root` is node 0. An empty scene has no nodes, no triangles,
// inverted root_bounds (lo = +inf, hi = -inf) and depth 0: since its root
// reference {0, 0} reads as "node 0", readers check `tris.empty()` first.
//
// Order: nodes depth-first in pre-order (a node before its children, the first
// child's subtree before the second's), so an interior first child is the next
// node; triangles in leaf order (the order a depth-first walk meets the leaves).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "datapath/triangle.h"
#include "scene/bvh_ref.h"
#include "scene/scene.h"
#include "scene/triangle_lanes.h"
#include "scene/wide_bvh_node.h"

namespace vbsim {

class WorkProgress;

struct alignas(64) BvhNode {
  float box[3][2][2];  ///< box[axis][0 low | 1 high][child]
  uint32_t ref[2];
  uint16_t count[2];
  uint32_t axis;

  /// What child `c` (0 or 1) refers to.
  BvhRef child(int c) const { return slot_ref(*this, c); }
  /// Child `c`'s box.
  Bounds3f child_bounds(int c) const { return slot_bounds(*this, c); }
  /// Stores child `c`'s box and reference (precondition: r.count <= 65535).
  void set_child(int c, const Bounds3f& b, BvhRef r) { set_slot(*this, c, b, r); }
};
static_assert(sizeof(BvhNode) == 64 && alignof(BvhNode) == 64,
              "BvhNode is 64 bytes, 64-byte aligned, in the hardware layout");
static_assert(offsetof(BvhNode, ref) == 48 && offsetof(BvhNode, count) == 56 && offsetof(BvhNode, axis) == 60,
              "BvhNode field offsets are part of the hardware layout");

struct BvhTriangle {
  Triangle tri;
  uint32_t prim;
};
static_assert(sizeof(BvhTriangle) == 40, "BvhTriangle is 40 bytes in the hardware layout");

/// Embree's build quality (RTCBuildQuality): Low is its Morton builder, Medium
/// and High its binned SAH builders; each gives another tree of the same scene.
enum class BvhQuality { Low, Medium, High };
const char* bvh_quality_name(BvhQuality q);              ///< "low", "medium", "high"
bool parse_bvh_quality(const std::string& s, BvhQuality& out);

/// Which builder makes the tree: Embree's rtcBuildBVH (of the options' quality),
/// or vbsim's own full-sweep SAH builder (sweep_sah_builder.h), which ignores the
/// quality. Both give the layout below.
enum class BvhBuilder { Embree, SweepSah };
const char* bvh_builder_name(BvhBuilder b);              ///< "embree", "sweep-sah"
bool parse_bvh_builder(const std::string& s, BvhBuilder& out);

/// The largest leaf Embree's builders make (RTC_BUILD_MAX_PRIMITIVES_PER_LEAF),
/// and the largest SAH traversal cost build_bvh takes.
constexpr int kMaxBvhLeafSize = 32;
constexpr float kMaxBvhTraversalCost = 1000.0f;
constexpr int kMaxBvhSahBlockSize = 16;

/// Two node precisions, as rtcore-systemc's tree has (scene/bvh_precision.h).
struct BvhPrecisionMarking {
  bool enabled = false;
  int mantissa_bits = 7;      ///< fraction bits a low-precision bound keeps (0..22; exponent: float32's)
  double t_trav_high = 0.5;   ///< SAH cost of a full-precision node test (a triangle test: 1)
  double t_trav_low = 0.47;   ///< SAH cost of a low-precision node test
  /// A node whose children are both low precision is tested in the narrow
  /// format itself, rounding widening the slabs (datapath/narrow_box_tester.h),
  /// as rtcore-systemc's low-precision units do; false: in float32 on the
  /// rounded boxes.
  bool narrow_arithmetic = false;
  bool operator==(const BvhPrecisionMarking& o) const {
    return enabled == o.enabled &&
           (!enabled || (mantissa_bits == o.mantissa_bits && t_trav_high == o.t_trav_high &&
                         t_trav_low == o.t_trav_low && narrow_arithmetic == o.narrow_arithmetic));
  }
};

/// Whether `n` may be BvhBuildOptions::sah_block_size: a power of two in
/// 1..kMaxBvhSahBlockSize (Embree's builder takes powers of two only).
inline bool valid_sah_block_size(int n) { return n >= 1 && n <= kMaxBvhSahBlockSize && (n & (n - 1)) == 0; }

struct BvhBuildOptions {
  int max_leaf_size = 4;  ///< triangles per leaf at most (1..kMaxBvhLeafSize)
  BvhQuality quality = BvhQuality::High;  ///< Embree's builder only
  BvhBuilder builder = BvhBuilder::Embree;
  /// The SAH's cost of a node step against one triangle test's 1 (Embree's
  /// traversalCost), in (0, kMaxBvhTraversalCost]: larger gives fewer, larger
  /// leaves (up to max_leaf_size).
  float traversal_cost = 1.0f;
  /// Nodes of two precisions (off by default: every box in float32).
  BvhPrecisionMarking low_precision{};
  /// Children per interior node the traversal reads: 2 (BvhNode), or 4 or 8
  /// (WideBvhNode, collapsed from the binary tree; scene/bvh_collapse.h).
  /// Nodes of two precisions are binary only.
  int width = 2;
  /// Triangles the SAH prices as one test (Embree's sahBlockSize): a leaf of
  /// n triangles costs ceil(n / sah_block_size) tests, and so does each side
  /// of a split. 1 for a triangle unit that takes one triangle an operation
  /// (the hardware model's); 4 as Embree prices its Triangle4 leaves, for a
  /// tester that takes four at once (the functional search's four-lane test).
  /// A power of two, 1..kMaxBvhSahBlockSize.
  int sah_block_size = 1;
  bool operator==(const BvhBuildOptions& o) const {
    return max_leaf_size == o.max_leaf_size && quality == o.quality && builder == o.builder &&
           traversal_cost == o.traversal_cost && sah_block_size == o.sah_block_size &&
           low_precision == o.low_precision && width == o.width;
  }
};

struct Bvh {
  std::vector<BvhNode> nodes;   ///< interior nodes, pre-order; node 0 is the root unless it is a leaf
  std::vector<BvhTriangle> tris;
  Bounds3f root_bounds;         ///< the root's box: the scene's triangles' exact bounds
  BvhRef root;                  ///< node 0, or the leaf that holds every triangle
  /// Levels on the longest root-to-leaf path, counting the leaf: the node fetches
  /// along that path plus one (a root leaf: 1; an empty scene: 0). Unchanged
  /// from the layout with one record per node, leaves included.
  int depth = 0;
  /// With nodes of two precisions (BvhBuildOptions::low_precision): per node,
  /// 1 when both its children's boxes are low-precision (rounded outward in
  /// the record), so the low-precision box pool tests it; empty otherwise.
  std::vector<uint8_t> low_precision_node;
  /// >= 0: the nodes low_precision_node marks are tested in the narrow format
  /// of this many fraction bits (BvhPrecisionMarking::narrow_arithmetic); -1: in float32.
  int narrow_mantissa_bits = -1;
  /// The node width traversal reads (BvhBuildOptions::width). At 4 (8) the
  /// binary `nodes` are still there (the oracle, the statistics and the
  /// converters read them) and `nodes4` (`nodes8`) holds the same tree
  /// collapsed: the same leaves, the same child boxes, node 0 the root; `root`
  /// refers to node 0 of either array, or to the same root leaf.
  int width = 2;
  std::vector<BvhNode4> nodes4;
  std::vector<BvhNode8> nodes8;
  /// Levels of the wide tree's longest root-to-leaf path, counting the leaf
  /// (width 2: depth).
  int wide_depth = 0;
  /// Interior nodes traversal reads at this width.
  size_t traversal_nodes() const { return width == 4 ? nodes4.size() : width == 8 ? nodes8.size() : nodes.size(); }
  /// Bytes of one node record traversal reads (one node fetch): 64, 128 or 256.
  uint32_t node_bytes() const {
    return width == 4 ? sizeof(BvhNode4) : width == 8 ? sizeof(BvhNode8) : sizeof(BvhNode);
  }
  /// The host copy of those records (node i at node_data() + i * node_bytes()).
  const char* node_data() const {
    return width == 4   ? reinterpret_cast<const char*>(nodes4.data())
           : width == 8 ? reinterpret_cast<const char*>(nodes8.data())
                        : reinterpret_cast<const char*>(nodes.data());
  }
  /// Whether the nodes low_precision_node marks are tested in the narrow format.
  bool narrow_nodes() const { return narrow_mantissa_bits >= 0 && !low_precision_node.empty(); }
  /// `tris`' coordinates as a structure of arrays, for the functional search's
  /// four-triangle leaf test (build_bvh fills it; a tree put together by hand
  /// may leave it empty, and a search then tests a triangle at a time; whoever
  /// changes `tris` afterwards fills it again, or empties it).
  TriangleLanes lanes;
  /// The lanes when they hold `tris`, else nullptr.
  const TriangleLanes* triangle_lanes() const { return lanes.size() == tris.size() ? &lanes : nullptr; }
};

/// Builds the BVH of `scene` with the options' builder: rtcBuildBVH (quality,
/// leaf size, traversal cost) or the sweep SAH (leaf size, traversal cost),
/// then marks its nodes' precisions when the options ask (bvh_precision.h)
/// and collapses it to the options' width (bvh_collapse.h), and fills its
/// triangle lanes;
/// std::invalid_argument when an option is out of range. Every
/// triangle appears in exactly one leaf; an empty scene gives no nodes and no triangles.
/// `progress`, when given, sees a step "building the BVH" (in triangles, as far
/// as Embree's builder reports its fraction done).
Bvh build_bvh(const Scene& scene, const BvhBuildOptions& options = {}, WorkProgress* progress = nullptr);

}  // namespace vbsim
