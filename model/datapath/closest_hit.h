// Closest-hit (and any-hit) search over the project's BVH: the BVH stepping of
// the datapath. Near child first along the node's split axis; a candidate the
// filter rejects does not shorten the interval. Box tests are the robust slab
// test (Ize 2013): the far distance is widened by 1 + 2 gamma(3) so that float
// rounding never culls a box the ray touches.
#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "datapath/candidate_filter.h"
#include "datapath/hit.h"
#include "datapath/ray.h"
#include "scene/bvh.h"

namespace vbsim {

/// Work one search did (node visits and triangle tests), for cost accounting.
struct TraversalCounters {
  uint64_t node_visits = 0;
  uint64_t box_tests = 0;
  uint64_t triangle_tests = 0;
  void add(const TraversalCounters& o) {
    node_visits += o.node_visits;
    box_tests += o.box_tests;
    triangle_tests += o.triangle_tests;
  }
};

constexpr int kTraversalStackDepth = 128;

/// Throws std::runtime_error when `bvh` is deeper than the traversal stack.
inline void check_traversal_depth(const Bvh& bvh) {
  if (bvh.depth >= kTraversalStackDepth)
    throw std::runtime_error("BVH depth exceeds the traversal stack of 128 entries");
}

/// Per-ray slab-test set-up: reciprocal direction.
struct RayBoxTester {
  Vec3f o, inv;
  explicit RayBoxTester(const Ray& ray) : o(ray.o), inv{1.0f / ray.d.x, 1.0f / ray.d.y, 1.0f / ray.d.z} {}
  /// True when the ray's interval [tmin, tmax] meets the node's box.
  bool hits(const BvhNode& n, float tmin, float tmax) const {
    constexpr float widen = 1.0f + 2.0f * (3.0f * 5.9604645e-8f) / (1.0f - 3.0f * 5.9604645e-8f);
    float tn = tmin, tf = tmax;
    for (int i = 0; i < 3; ++i) {
      const float t0 = (n.lo[i] - o[i]) * inv[i];
      const float t1 = (n.hi[i] - o[i]) * inv[i];
      // A NaN (origin on a slab plane with d_i = 0) drops out of both bounds.
      tn = std::max(tn, std::min(t0, t1));
      tf = std::min(tf, std::max(t0, t1) * widen);
    }
    return tn <= tf;
  }
};

/// Closest accepted hit of `ray` (any accepted hit when `any_hit`); miss: prim -1.
template <class Tester>
Hit closest_hit(const Bvh& bvh, const Ray& ray, const CandidateFilter& filter,
                CandidateCounters& cc, TraversalCounters& tc, bool any_hit = false) {
  Hit best;
  if (bvh.tris.empty()) return best;  // an empty scene: its single leaf holds nothing
  const Tester tester(ray);
  const RayBoxTester box(ray);
  float tmax = ray.tmax;
  uint32_t stack[kTraversalStackDepth];
  int sp = 0;
  uint32_t node = 0;
  for (;;) {
    const BvhNode& n = bvh.nodes[node];
    ++tc.node_visits;
    ++tc.box_tests;
    if (box.hits(n, ray.tmin, tmax)) {
      if (!n.is_leaf()) {
        const bool second_first = ray.d[static_cast<int>(n.axis())] < 0.0f;
        const uint32_t first = node + 1, second = n.offset;
        stack[sp++] = second_first ? first : second;
        node = second_first ? second : first;
        continue;
      }
      for (uint32_t i = n.offset, end = n.offset + n.count(); i < end; ++i) {
        const BvhTriangle& bt = bvh.tris[i];
        ++tc.triangle_tests;
        Hit h;
        if (!tester.intersect(bt.tri, tmax, h)) continue;
        h.prim = static_cast<int32_t>(bt.prim);
        if (!filter.accept(ray, bt.tri, h.prim, h, cc)) continue;
        best = h;
        tmax = h.t;
        if (any_hit) return best;
      }
    }
    if (sp == 0) break;
    node = stack[--sp];
  }
  return best;
}

}  // namespace vbsim
