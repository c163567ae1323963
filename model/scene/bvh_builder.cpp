// build_bvh: checks the options and hands a sweep-SAH build to
// sweep_sah_builder.cpp; otherwise Embree's rtcBuildBVH (binned SAH at high
// quality by default, or the options' quality and leaf size; branching factor 2)
// builds a temporary tree in Embree's thread-local allocator; this file then
// flattens it depth-first into the layout documented in bvh.h.
//
// Choices beyond bvh.h (contract for traversal code; sweep_sah_builder.cpp keeps
// them too, with bvh_build_common.h):
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
#include <thread>

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include "progress/work_progress.h"
#include "scene/bvh.h"
#include "scene/bvh_build_common.h"
#include "scene/bvh_collapse.h"
#include "scene/bvh_precision.h"
#include "scene/embree_device.h"
#include "scene/sweep_sah_builder.h"

namespace vbsim {

namespace {

using bvh_build::check_options;
using bvh_build::checked_triangle_bounds;
using bvh_build::ChildOrder;
using bvh_build::merge;
using bvh_build::order_children;

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
  WorkProgress* progress = nullptr;  // told on the building thread only
  std::thread::id building_thread;
  uint64_t triangles = 0;
};

// Embree's progress monitor: the fraction done, as triangles; never cancels.
bool report_build_progress(void* user, double fraction) {
  auto* context = static_cast<BuildContext*>(user);
  if (context->progress && std::this_thread::get_id() == context->building_thread)
    context->progress->update(static_cast<uint64_t>(fraction * static_cast<double>(context->triangles)));
  return true;
}

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

// Fills BuildNode::bounds bottom-up; throws if the tree is malformed.
void compute_bounds(BuildNode* node, const Scene& scene) {
  if (node == nullptr) throw SceneError("Embree rtcBuildBVH returned an incomplete tree");
  if (node->count != 0) {
    for (uint32_t i = 0; i < node->count; ++i) {
      if (node->prims[i] >= static_cast<uint32_t>(scene.size()))
        throw SceneError(fmt::format("Embree rtcBuildBVH returned unknown primitive {}", node->prims[i]));
      node->bounds = merge(node->bounds, checked_triangle_bounds(scene, node->prims[i]));
    }
    return;
  }
  compute_bounds(node->children[0], scene);
  compute_bounds(node->children[1], scene);
  node->bounds = merge(node->children[0]->bounds, node->children[1]->bounds);
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
  const ChildOrder order = order_children(first->bounds, second->bounds);
  if (order.swap) std::swap(first, second);
  const BvhRef first_ref = flatten(first, depth + 1, scene, bvh);
  const BvhRef second_ref = flatten(second, depth + 1, scene, bvh);
  BvhNode& n = bvh.nodes[index];  // taken after the recursion: `nodes` may have grown
  n.set_child(0, first->bounds, first_ref);
  n.set_child(1, second->bounds, second_ref);
  n.axis = static_cast<uint32_t>(order.axis);
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

const char* bvh_builder_name(BvhBuilder b) { return b == BvhBuilder::SweepSah ? "sweep-sah" : "embree"; }

bool parse_bvh_builder(const std::string& s, BvhBuilder& out) {
  for (BvhBuilder b : {BvhBuilder::Embree, BvhBuilder::SweepSah})
    if (s == bvh_builder_name(b)) {
      out = b;
      return true;
    }
  return false;
}

namespace {

/// The tree of the options' builder, every box in float32.
Bvh build_tree(const Scene& scene, const BvhBuildOptions& options, WorkProgress* progress);

}  // namespace

Bvh build_bvh(const Scene& scene, const BvhBuildOptions& options, WorkProgress* progress) {
  check_options(options);
  if (options.low_precision.enabled) check_bvh_precision(options.low_precision);
  Bvh bvh = build_tree(scene, options, progress);
  if (options.low_precision.enabled) mark_low_precision(bvh, options.low_precision);
  collapse_bvh(bvh, options.width);
  bvh.lanes.fill(bvh.tris.data(), bvh.tris.size());
  return bvh;
}

namespace {

Bvh build_tree(const Scene& scene, const BvhBuildOptions& options, WorkProgress* progress) {
  if (options.builder == BvhBuilder::SweepSah) {
    if (progress) progress->begin("building the BVH (sweep SAH)", 0, "");
    return build_sweep_sah_bvh(scene, options);
  }

  Bvh bvh;
  if (scene.triangles.empty()) return bvh;  // no nodes, no triangles, depth 0
  if (progress) progress->begin("building the BVH", scene.triangles.size(), "triangles");

  std::vector<RTCBuildPrimitive> prims(scene.triangles.size());
  float largest = 0.0f;  // largest |coordinate|
  for (size_t i = 0; i < prims.size(); ++i) {
    const Bounds3f b = checked_triangle_bounds(scene, i);
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
  args.sahBlockSize = static_cast<unsigned>(options.sah_block_size);
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
  if (progress) {
    context.progress = progress;
    context.building_thread = std::this_thread::get_id();
    context.triangles = prims.size();
    args.buildProgress = report_build_progress;
  }

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

}  // namespace

}  // namespace vbsim
