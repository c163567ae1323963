#include "scene/bvh_stats.h"

#include <algorithm>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "scene/bvh_build_common.h"

namespace vbsim {

namespace {

using bvh_build::surface_area;

struct Pending {
  BvhRef ref;
  Bounds3f box;  // the subtree's box
  int depth;     // levels from the root (1), leaves included
};

}  // namespace

BvhStats compute_bvh_stats(const Bvh& bvh) {
  BvhStats s;
  s.nodes = static_cast<int64_t>(bvh.nodes.size());
  s.triangles = static_cast<int64_t>(bvh.tris.size());
  s.node_bytes = s.nodes * static_cast<int64_t>(sizeof(BvhNode));
  s.triangle_bytes = s.triangles * static_cast<int64_t>(sizeof(BvhTriangle));
  s.width = bvh.width;
  s.wide_nodes = static_cast<int64_t>(bvh.traversal_nodes());
  s.wide_node_bytes = s.wide_nodes * bvh.node_bytes();
  s.wide_depth = bvh.width == 2 ? bvh.depth : bvh.wide_depth;
  if (bvh.tris.empty()) return s;  // build_bvh's empty scene: no nodes, no leaves, depth 0

  const double root_area = surface_area(bvh.root_bounds);
  std::vector<Pending> stack{{bvh.root, bvh.root_bounds, 1}};
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    s.depth = std::max(s.depth, p.depth);
    const double weight = root_area > 0 ? surface_area(p.box) / root_area : 1.0;
    if (p.ref.is_leaf()) {
      ++s.leaves;
      s.max_leaf_size = std::max<int64_t>(s.max_leaf_size, p.ref.count);
      s.sah_cost += kSahIntersectionCost * p.ref.count * weight;
      continue;
    }
    s.sah_cost += kSahTraversalCost * weight;
    const BvhNode& n = bvh.nodes[p.ref.index];
    for (int c = 1; c >= 0; --c) stack.push_back({n.child(c), n.child_bounds(c), p.depth + 1});
  }
  s.average_leaf_size = s.leaves > 0 ? double(s.triangles) / double(s.leaves) : 0.0;
  return s;
}

std::string format_bvh_stats(const BvhStats& s) {
  return fmt::format(
      "nodes: {}\nleaves: {}\ntriangles: {}\naverage leaf size: {:.3f} triangles\n"
      "max leaf size: {} triangles\ndepth: {} levels\nnode bytes: {} B\ntriangle bytes: {} B\n"
      "SAH cost: {:.3f}\nwidth: {}\nwide nodes: {}\nwide node bytes: {} B\nwide depth: {} levels\n",
      s.nodes, s.leaves, s.triangles, s.average_leaf_size, s.max_leaf_size, s.depth, s.node_bytes,
      s.triangle_bytes, s.sah_cost, s.width, s.wide_nodes, s.wide_node_bytes, s.wide_depth);
}

}  // namespace vbsim
