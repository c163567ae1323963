// Closest-hit (and any-hit) search over the project's BVH: the BVH stepping of
// the datapath. Over a 4- or 8-wide tree it is wide_closest_hit.h's; over the
// binary one, one node fetch gives both children's boxes (bvh.h); the nearer
// child is visited first; a candidate the filter rejects does not shorten the
// interval. Box tests are the robust slab test of ray_box_tester.h.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "datapath/candidate_filter.h"
#include "datapath/hit.h"
#include "datapath/narrow_box_tester.h"
#include "datapath/ray.h"
#include "datapath/ray_box_tester.h"
#include "datapath/search_rules.h"
#include "datapath/wide_closest_hit.h"
#include "scene/bvh.h"

namespace vbsim {

/// A binary node's two box tests: float32 (RayBoxTester) for every node.
struct FloatNodeBoxes {
  explicit FloatNodeBoxes(const Bvh&, const Ray&) {}
  unsigned hits(const RayBoxTester& box, uint32_t, const BvhNode& n, float tmax, float& t0, float& t1) const {
    return box.hits(n, tmax, t0, t1);
  }
};

/// ... and with the nodes Bvh::low_precision_node marks tested in the narrow
/// format (Bvh::narrow_mantissa_bits >= 0; datapath/narrow_box_tester.h).
struct NarrowNodeBoxes {
  NarrowBoxTester narrow;
  const uint8_t* marked;
  NarrowNodeBoxes(const Bvh& bvh, const Ray& ray)
      : narrow(ray, bvh.narrow_mantissa_bits), marked(bvh.low_precision_node.data()) {}
  unsigned hits(const RayBoxTester& box, uint32_t index, const BvhNode& n, float tmax, float& t0, float& t1) const {
    return marked[index] ? narrow.hits(n, tmax, t0, t1) : box.hits(n, tmax, t0, t1);
  }
};

/// The binary search with node box tests `Boxes` (closest_hit below): each
/// interior node is one fetch that tests both children's boxes; the nearer
/// child is visited first and the farther is skipped later if a hit has come
/// closer than its entry.
template <class Tester, class Boxes>
Hit binary_closest_hit(const Bvh& bvh, const Ray& ray, const CandidateFilter& filter, CandidateCounters& cc,
                       TraversalCounters& tc, bool any_hit) {
  Hit best;
  if (bvh.tris.empty()) return best;  // an empty scene: no root to read
  const Tester tester(ray);
  const RayBoxTester box(ray);
  const Boxes boxes(bvh, ray);
  float tmax = ray.tmax;
  struct Entry {  // trivial, so the stack is not cleared per ray
    uint32_t index, count;  // a BvhRef
    float t;
  } stack[kTraversalStackDepth];
  int sp = 0;
  // Counted locally and added once: the search's inner loop stays in registers.
  uint64_t node_visits = 0, triangle_tests = 0, pushes = 0;
  const auto finish = [&] {
    tc.node_visits += node_visits;
    tc.box_tests += 1 + 2 * node_visits;  // the root's box, then two per fetch
    tc.triangle_tests += triangle_tests;
    tc.stack_pushes += pushes;
    tc.stack_pops += pushes - static_cast<uint64_t>(sp);  // what is left was never popped
    return best;
  };
  if (!box.hits(bvh.root_bounds, cull_limit(tmax))) return finish();
  // Held in registers: the tester's out-of-line calls could otherwise force re-reads.
  const BvhNode* const nodes = bvh.nodes.data();
  const BvhTriangle* const tris = bvh.tris.data();
  const TriangleLanes* const lanes = bvh.triangle_lanes();
  BvhRef ref = bvh.root;
  for (;;) {
    if (!ref.is_leaf()) {
      const BvhNode& n = nodes[ref.index];
      ++node_visits;
      float t0, t1;
      const unsigned hit = boxes.hits(box, ref.index, n, cull_limit(tmax), t0, t1);
      if (hit != 0u) {
        // Descend into the nearer child met (child 0 on a tie) and write the
        // other to the stack, keeping it only when both were met. Selects, not
        // loads indexed by the test's outcome: measured faster.
        const bool first0 = hit == 1u || (hit == 3u && t0 <= t1);
        const BvhRef c0 = n.child(0), c1 = n.child(1);
        const BvhRef far = first0 ? c1 : c0;
        stack[sp].index = far.index;
        stack[sp].count = far.count;
        stack[sp].t = first0 ? t1 : t0;
        sp += hit == 3u;
        pushes += hit == 3u;
        ref = first0 ? c0 : c1;
        continue;
      }
    } else if (search_leaf(tris, lanes, ref, tester, ray, filter, cc, any_hit, best, tmax, triangle_tests)) {
      return finish();
    }
    if (!pop_reachable(stack, sp, tmax, ref)) return finish();
  }
}

/// Closest accepted hit of `ray` (any accepted hit when `any_hit`); miss: prim -1;
/// at equal distances the lowest primitive id (ties, above).
template <class Tester>
Hit closest_hit(const Bvh& bvh, const Ray& ray, const CandidateFilter& filter,
                CandidateCounters& cc, TraversalCounters& tc, bool any_hit = false) {
  if (bvh.width == 4) return wide_closest_hit<4, Tester>(bvh, ray, filter, cc, tc, any_hit);
  if (bvh.width == 8) return wide_closest_hit<8, Tester>(bvh, ray, filter, cc, tc, any_hit);
  if (__builtin_expect(bvh.narrow_nodes(), 0))
    return binary_closest_hit<Tester, NarrowNodeBoxes>(bvh, ray, filter, cc, tc, any_hit);
  return binary_closest_hit<Tester, FloatNodeBoxes>(bvh, ray, filter, cc, tc, any_hit);
}

}  // namespace vbsim
