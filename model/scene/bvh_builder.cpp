// build_bvh: Embree's rtcBuildBVH (binned SAH at high quality by default, or the
// options' quality and leaf size; branching factor 2)
// builds a temporary tree in Embree's thread-local allocator; this file then
// flattens it depth-first into the layout documented in bvh.h.
//
// Choices beyond bvh.h (contract for traversal code):
//   - Boxes (child slots and root_bounds) are the exact float32 min/max of the
//     vertices of the triangles below them, recomputed here (never taken from,
//     or shrunk to, anything else).
//   - Split axis of an interior node: the axis along which the centres of the two
//     children's boxes differ most (ties: lowest axis). The children are ordered
//     so that child 0's centre is not greater than child 1's on that axis; a ray
//     with d[axis] >= 0 meets child 0's side first.
//   - Every interior node has two non-empty children: no empty slots.
//   - An empty scene gives no nodes and no triangles (bvh.h).
//   - No spatial splits: each triangle is in exactly one leaf.
//   - The build runs on one Embree thread (see EmbreeDevice), so it is reproducible.
#include <atomic>
#include <cmath>
#include <algorithm>
#include <new>
#include <stdexcept>

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include "scene/bvh.h"
#include "scene/embree_device.h"

namespace vbsim {

namespace {

constexpr unsigned kMaxDepth = 32;  // Embree's default depth limit for rtcBuildBVH

// Temporary node, allocated in Embree's thread-local allocator (freed with the RTCBVH).
struct BuildNode {
  BuildNode* children[2];
  uint32_t count;         // 0: interior node
  const uint32_t* prims;  // leaf: scene triangle ids, `count` of them
  Bounds3f bounds;        // exact, filled by compute_bounds()
};

// Shared with the callbacks; they run on Embree's threads and cannot throw.
struct BuildContext {
  std::atomic<bool> unexpected_shape{false};  // a node with other than 2 children
  std::atomic<bool> out_of_memory{false};
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned child_count, void* user) {
  auto* context = static_cast<BuildContext*>(user);
  void* memory = rtcThreadLocalAlloc(alloc, sizeof(BuildNode), alignof(BuildNode));
  if (memory == nullptr) {
    context->out_of_memory = true;
    return nullptr;
  }
  if (child_count != 2) context->unexpected_shape = true;
  return new (memory) BuildNode{{nullptr, nullptr}, 0, nullptr, {}};
}

void set_node_children(void* node, void** children, unsigned child_count, void* user) {
  auto* context = static_cast<BuildContext*>(user);
  if (node == nullptr) return;
  if (child_count != 2) {
    context->unexpected_shape = true;
    return;
  }
  auto* n = static_cast<BuildNode*>(node);
  n->children[0] = static_cast<BuildNode*>(children[0]);
  n->children[1] = static_cast<BuildNode*>(children[1]);
}

// Embree's child bounds are not used: bounds are recomputed from the triangles.
void set_node_bounds(void*, const RTCBounds**, unsigned, void*) {}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void* user) {
  auto* context = static_cast<BuildContext*>(user);
  void* memory = rtcThreadLocalAlloc(alloc, sizeof(BuildNode), alignof(BuildNode));
  auto* ids = static_cast<uint32_t*>(rtcThreadLocalAlloc(alloc, count * sizeof(uint32_t), alignof(uint32_t)));
  if (memory == nullptr || ids == nullptr) {
    context->out_of_memory = true;
    return nullptr;
  }
  for (size_t i = 0; i < count; ++i) ids[i] = prims[i].primID;
  return new (memory) BuildNode{{nullptr, nullptr}, static_cast<uint32_t>(count), ids, {}};
}

Bounds3f triangle_bounds(const Triangle& t) {
  Bounds3f b;
  b.extend(t.v0);
  b.extend(t.v1);
  b.extend(t.v2);
  return b;
}

Bounds3f merge(const Bounds3f& a, const Bounds3f& b) {
  Bounds3f m = a;
  m.extend(b.lo);
  m.extend(b.hi);
  return m;
}

// Fills BuildNode::bounds bottom-up; throws if the tree is malformed.
void compute_bounds(BuildNode* node, const Scene& scene) {
  if (node == nullptr) throw SceneError("Embree rtcBuildBVH returned an incomplete tree");
  if (node->count != 0) {
    for (uint32_t i = 0; i < node->count; ++i) {
      if (node->prims[i] >= static_cast<uint32_t>(scene.size()))
        throw SceneError(fmt::format("Embree rtcBuildBVH returned unknown primitive {}", node->prims[i]));
      node->bounds = merge(node->bounds, triangle_bounds(scene.triangles[node->prims[i]]));
    }
    return;
  }
  compute_bounds(node->children[0], scene);
  compute_bounds(node->children[1], scene);
  node->bounds = merge(node->children[0]->bounds, node->children[1]->bounds);
}

double centre(const Bounds3f& b, int axis) { return 0.5 * (double(b.lo[axis]) + double(b.hi[axis])); }

// Axis along which the two boxes' centres differ most (ties: lowest axis).
int split_axis(const Bounds3f& a, const Bounds3f& b) {
  int best = 0;
  double best_gap = -1.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double gap = std::fabs(centre(a, axis) - centre(b, axis));
    if (gap > best_gap) best = axis, best_gap = gap;
  }
  return best;
}

// Appends `node`'s subtree (nodes in pre-order, triangles in leaf order) and
// returns its reference; `depth` counts levels from the root (1), leaves included.
BvhRef flatten(const BuildNode* node, int depth, const Scene& scene, Bvh& bvh) {
  bvh.depth = std::max(bvh.depth, depth);
  if (node->count != 0) {
    const auto first = static_cast<uint32_t>(bvh.tris.size());
    for (uint32_t i = 0; i < node->count; ++i)
      bvh.tris.push_back(BvhTriangle{scene.triangles[node->prims[i]], node->prims[i]});
    return BvhRef{first, node->count};
  }
  const auto index = static_cast<uint32_t>(bvh.nodes.size());
  bvh.nodes.emplace_back();
  const BuildNode* first = node->children[0];
  const BuildNode* second = node->children[1];
  const int axis = split_axis(first->bounds, second->bounds);
  if (centre(second->bounds, axis) < centre(first->bounds, axis)) std::swap(first, second);
  const BvhRef first_ref = flatten(first, depth + 1, scene, bvh);
  const BvhRef second_ref = flatten(second, depth + 1, scene, bvh);
  BvhNode& n = bvh.nodes[index];  // taken after the recursion: `nodes` may have grown
  n.set_child(0, first->bounds, first_ref);
  n.set_child(1, second->bounds, second_ref);
  n.axis = static_cast<uint32_t>(axis);
  return BvhRef{index, 0};
}

// Embree's builder computes box areas and SAH costs in float32: they underflow
// to 0 for scenes whose coordinates are all tiny (the bunny scaled by 1e-25:
// "depth limit reached") and overflow for huge ones. The boxes it sees are
// therefore scaled by a power of two, which is exact for normal floats, so that
// the largest |coordinate| lies in [1, 2) whenever it is outside
// [2^-32, 2^32]; scenes inside that range are handed over as they are. Only the
// tree's shape comes from Embree (bounds are recomputed from the triangles),
// so the scale changes no box that traversal tests.
void scale_for_builder(std::vector<RTCBuildPrimitive>& prims, float largest) {
  if (largest == 0.0f || (largest >= 0x1p-32f && largest <= 0x1p32f)) return;
  int exponent = 0;
  std::frexp(largest, &exponent);  // largest = m * 2^exponent, m in [0.5, 1)
  const int shift = 1 - exponent;  // largest * 2^shift in [1, 2)
  for (RTCBuildPrimitive& p : prims) {
    p.lower_x = std::ldexp(p.lower_x, shift);
    p.lower_y = std::ldexp(p.lower_y, shift);
    p.lower_z = std::ldexp(p.lower_z, shift);
    p.upper_x = std::ldexp(p.upper_x, shift);
    p.upper_y = std::ldexp(p.upper_y, shift);
    p.upper_z = std::ldexp(p.upper_z, shift);
  }
}

// Owns an RTCBVH (and with it every BuildNode).
struct BvhHandle {
  RTCBVH bvh;
  ~BvhHandle() {
    if (bvh) rtcReleaseBVH(bvh);
  }
};

}  // namespace

const char* bvh_quality_name(BvhQuality q) {
  return q == BvhQuality::Low ? "low" : q == BvhQuality::Medium ? "medium" : "high";
}

bool parse_bvh_quality(const std::string& s, BvhQuality& out) {
  for (BvhQuality q : {BvhQuality::Low, BvhQuality::Medium, BvhQuality::High})
    if (s == bvh_quality_name(q)) {
      out = q;
      return true;
    }
  return false;
}

Bvh build_bvh(const Scene& scene, const BvhBuildOptions& options) {
  if (!(options.traversal_cost > 0 && options.traversal_cost <= kMaxBvhTraversalCost))
    throw std::invalid_argument(fmt::format("BvhBuildOptions.traversal_cost must be in (0, {}], got {}",
                                            kMaxBvhTraversalCost, options.traversal_cost));
  if (options.max_leaf_size < 1 || options.max_leaf_size > kMaxBvhLeafSize)
    throw std::invalid_argument(fmt::format("BvhBuildOptions.max_leaf_size must be in 1..{}, got {}",
                                            kMaxBvhLeafSize, options.max_leaf_size));

  Bvh bvh;
  if (scene.triangles.empty()) return bvh;  // no nodes, no triangles, depth 0

  std::vector<RTCBuildPrimitive> prims(scene.triangles.size());
  float largest = 0.0f;  // largest |coordinate|
  for (size_t i = 0; i < prims.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    if (!is_finite(t.v0) || !is_finite(t.v1) || !is_finite(t.v2))
      throw SceneError(fmt::format("scene '{}': triangle {} has a non-finite vertex", scene.source, i));
    const Bounds3f b = triangle_bounds(t);
    for (int axis = 0; axis < 3; ++axis)
      largest = std::max({largest, std::fabs(b.lo[axis]), std::fabs(b.hi[axis])});
    prims[i] = RTCBuildPrimitive{b.lo.x, b.lo.y, b.lo.z, 0u, b.hi.x, b.hi.y, b.hi.z, static_cast<unsigned>(i)};
  }
  scale_for_builder(prims, largest);

  EmbreeDevice device;
  BvhHandle handle{rtcNewBVH(device.get())};
  device.check("rtcNewBVH");

  BuildContext context;
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = options.quality == BvhQuality::Low      ? RTC_BUILD_QUALITY_LOW
                      : options.quality == BvhQuality::Medium ? RTC_BUILD_QUALITY_MEDIUM
                                                              : RTC_BUILD_QUALITY_HIGH;
  args.maxBranchingFactor = 2;
  args.maxDepth = kMaxDepth;
  args.minLeafSize = 1;
  args.maxLeafSize = static_cast<unsigned>(options.max_leaf_size);
  args.traversalCost = options.traversal_cost;
  args.intersectionCost = 1.0f;
  args.bvh = handle.bvh;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();  // no room for spatial splits: none happen
  args.createNode = create_node;
  args.setNodeChildren = set_node_children;
  args.setNodeBounds = set_node_bounds;
  args.createLeaf = create_leaf;
  args.splitPrimitive = nullptr;
  args.userPtr = &context;

  auto* root = static_cast<BuildNode*>(rtcBuildBVH(&args));
  try {
    device.check("rtcBuildBVH");
  } catch (const SceneError& e) {
    throw SceneError(fmt::format("scene '{}': {}", scene.source, e.what()));
  }
  if (context.out_of_memory) throw SceneError("Embree rtcBuildBVH: out of memory for BVH nodes");
  if (context.unexpected_shape) throw SceneError("Embree rtcBuildBVH built a node without exactly 2 children");

  compute_bounds(root, scene);
  bvh.nodes.reserve(prims.size());
  bvh.tris.reserve(prims.size());
  bvh.root_bounds = root->bounds;
  bvh.root = flatten(root, 1, scene, bvh);
  if (bvh.tris.size() != scene.triangles.size())
    throw SceneError(fmt::format("Embree rtcBuildBVH placed {} of {} triangles in leaves", bvh.tris.size(),
                                 scene.triangles.size()));
  return bvh;
}

}  // namespace vbsim
