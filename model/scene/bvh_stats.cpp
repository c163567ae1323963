#include "scene/bvh_stats.h"

#include <algorithm>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace vbsim {

namespace {

double surface_area(const BvhNode& n) {
  const double dx = double(n.hi[0]) - n.lo[0], dy = double(n.hi[1]) - n.lo[1], dz = double(n.hi[2]) - n.lo[2];
  if (dx < 0 || dy < 0 || dz < 0) return 0.0;
  return 2.0 * (dx * dy + dy * dz + dz * dx);
}

}  // namespace

BvhStats compute_bvh_stats(const Bvh& bvh) {
  BvhStats s;
  s.nodes = static_cast<int64_t>(bvh.nodes.size());
  s.triangles = static_cast<int64_t>(bvh.tris.size());
  s.node_bytes = s.nodes * static_cast<int64_t>(sizeof(BvhNode));
  s.triangle_bytes = s.triangles * static_cast<int64_t>(sizeof(BvhTriangle));
  if (bvh.tris.empty()) {  // build_bvh's empty scene: one node standing for an empty leaf
    s.leaves = s.nodes > 0 ? 1 : 0;
    s.depth = s.nodes > 0 ? 1 : 0;
    return s;
  }

  const double root_area = surface_area(bvh.nodes[0]);
  std::vector<std::pair<uint32_t, int>> stack{{0u, 1}};  // node index, depth in nodes
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    const BvhNode& n = bvh.nodes[index];
    s.depth = std::max(s.depth, depth);
    const double weight = root_area > 0 ? surface_area(n) / root_area : 1.0;
    if (n.is_leaf()) {
      ++s.leaves;
      s.max_leaf_size = std::max<int64_t>(s.max_leaf_size, n.count());
      s.sah_cost += kSahIntersectionCost * n.count() * weight;
    } else {
      s.sah_cost += kSahTraversalCost * weight;
      stack.push_back({n.offset, depth + 1});
      stack.push_back({index + 1, depth + 1});
    }
  }
  s.average_leaf_size = s.leaves > 0 ? double(s.triangles) / double(s.leaves) : 0.0;
  return s;
}

std::string format_bvh_stats(const BvhStats& s) {
  return fmt::format(
      "nodes: {}\nleaves: {}\ntriangles: {}\naverage leaf size: {:.3f} triangles\n"
      "max leaf size: {} triangles\ndepth: {} nodes\nnode bytes: {} B\ntriangle bytes: {} B\n"
      "SAH cost: {:.3f}\n",
      s.nodes, s.leaves, s.triangles, s.average_leaf_size, s.max_leaf_size, s.depth, s.node_bytes,
      s.triangle_bytes, s.sah_cost);
}

}  // namespace vbsim
