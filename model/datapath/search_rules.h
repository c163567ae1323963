// The rules every closest-hit search over the project's BVH keeps, whatever
// its node width: the work counters, the stack depth, and how ties and the
// culling bound are decided (so that the hit does not depend on the tree).
#pragma once
#include <cstdint>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>

#include "datapath/candidate_filter.h"
#include "datapath/hit.h"
#include "datapath/ray.h"
#include "datapath/ray_box_tester.h"
#include "datapath/three_half_plane_lanes.h"
#include "scene/bvh.h"
#include "scene/triangle_lanes.h"

namespace vbsim {

/// Work one search did, for cost accounting.
struct TraversalCounters {
  uint64_t node_visits = 0;     ///< node fetches: one per interior node visited (of the tree's width)
  uint64_t box_tests = 0;       ///< the root's box, then every used child slot's box of every node fetched
  uint64_t triangle_tests = 0;  ///< triangles handed to the tester
  uint64_t stack_pushes = 0;    ///< farther children pushed (both children met)
  uint64_t stack_pops = 0;      ///< entries popped (the search ends with the rest unpopped)
  void add(const TraversalCounters& o) {
    node_visits += o.node_visits;
    box_tests += o.box_tests;
    triangle_tests += o.triangle_tests;
    stack_pushes += o.stack_pushes;
    stack_pops += o.stack_pops;
  }
};

constexpr int kTraversalStackDepth = 128;

/// Whether `Tester` has a four-lane form (LaneHits and intersect_lanes; the
/// three-half-plane tester on an SSE2 host).
template <class Tester, class = void>
struct HasLaneForm : std::false_type {};
template <class Tester>
struct HasLaneForm<Tester, std::void_t<typename Tester::LaneHits>> : std::true_type {};

// Ties. A closest-hit search keeps, of candidates at the same distance, the one
// of the lowest primitive id, so that its hit does not depend on the order the
// tree presents triangles in (any BVH gives the same hit; docs/hw-model.md,
// "The BVH"). Once it holds a hit at `tmax`, the tester is asked for an
// interval a few ulps beyond tmax (candidate_limit: a tester's scaled interval
// check rounds, and must not drop a candidate whose distance comes out at tmax),
// and of what it answers only a candidate before tmax, or at tmax with a lower
// id, is taken (nearer_than_best). Boxes are culled
// only beyond cull_limit(tmax), tmax widened as the box test widens a box's exit:
// a box's entry and a triangle on its face are rounded apart by a few ulps, and
// a box entered just beyond the hit must still be visited for a triangle at the
// hit's distance to be found whatever box holds it.
// An any-hit search stops at the first accepted hit, whatever its id.

/// The distance beyond which boxes and stack entries are culled (above).
inline float cull_limit(float tmax) { return tmax * RayBoxTester::kWiden; }

/// The upper bound to test a triangle against: the ray's tmax, or once the
/// search holds a hit at tmax, cull_limit(tmax) (so that a tie is seen).
inline float candidate_limit(const Hit& best, float tmax) { return best.prim >= 0 ? cull_limit(tmax) : tmax; }

/// Whether candidate `h` (inside candidate_limit) is nearer than `best` at
/// `tmax`: closer, or at the same distance with a lower primitive id.
inline bool nearer_than_best(const Hit& h, const Hit& best, float tmax) {
  return h.t < tmax || (h.t == tmax && best.prim >= 0 && h.prim < best.prim);
}

/// Throws std::runtime_error when `bvh` is deeper than the traversal stack. A
/// binary search keeps at most one stack entry per node fetched on its current
/// path, so at most depth - 1 entries (Bvh::depth counts the leaf's level too),
/// and it writes one slot past the kept entries at every fetch: depth - 1 must
/// stay below kTraversalStackDepth. A W-wide search keeps at most W - 1 entries
/// per node on its path: (W - 1) (wide_depth - 1) must not exceed it.
inline void check_traversal_depth(const Bvh& bvh) {
  if (bvh.width == 2 ? bvh.depth - 1 >= kTraversalStackDepth
                     : (bvh.width - 1) * (bvh.wide_depth - 1) > kTraversalStackDepth)
    throw std::runtime_error(fmt::format(
        "BVH too deep for the traversal stack of {} entries: width {}, {} levels (a {}-wide search may keep {} entries)",
        kTraversalStackDepth, bvh.width, bvh.width == 2 ? bvh.depth : bvh.wide_depth, bvh.width,
        bvh.width == 2 ? bvh.depth - 1 : (bvh.width - 1) * (bvh.wide_depth - 1)));
}

/// A candidate `h` of triangle `bt`, found below candidate_limit(best, tmax):
/// the tie rule, then the filter; an accepted one becomes the best and
/// shortens the interval. True when it was accepted.
__attribute__((always_inline)) inline bool take_candidate(Hit h, const BvhTriangle& bt, const Ray& ray,
                                                          const CandidateFilter& filter, CandidateCounters& cc,
                                                          Hit& best, float& tmax) {
  h.prim = static_cast<int32_t>(bt.prim);
  if (!nearer_than_best(h, best, tmax)) return false;  // a tie with a lower id already held
  if (!filter.accept(ray, bt.tri, h.prim, h, cc)) return false;
  best = h;
  tmax = h.t;
  return true;
}

/// search_leaf four triangles at a time: each group is tested once against
/// cull_limit(tmax) (no later candidate_limit in the leaf exceeds it, as tmax
/// only shrinks), then its candidates are taken in order, each held again to
/// the limit of its turn (LaneHits::below: the tester's own upper-bound checks
/// and its division, so the answer is intersect()'s with that limit); a lane that needs the
/// tester's exact redo is tested by intersect() itself.
template <class Tester>
__attribute__((always_inline)) inline bool search_leaf_lanes(const BvhTriangle* tris, const TriangleLanes& lanes,
                                                             BvhRef leaf, const Tester& tester, const Ray& ray,
                                                             const CandidateFilter& filter, CandidateCounters& cc,
                                                             bool any_hit, Hit& best, float& tmax,
                                                             uint64_t& triangle_tests) {
  for (uint32_t g = leaf.index, end = leaf.index + leaf.count; g < end; g += 4) {
    const int n = end - g < 4u ? static_cast<int>(end - g) : 4;
    typename Tester::LaneHits lh;
    tester.intersect_lanes(lanes, g, n, cull_limit(tmax), lh);
    for (unsigned todo = lh.met | lh.redo; todo != 0u; todo &= todo - 1u) {
      const int l = __builtin_ctz(todo);
      const BvhTriangle& bt = tris[g + static_cast<uint32_t>(l)];
      const float limit = candidate_limit(best, tmax);
      Hit h;
      if ((lh.redo >> l) & 1u) {
        if (!tester.intersect(bt.tri, limit, h)) continue;
      } else {
        if (!lh.below(l, limit)) continue;
        h = lh.hit(l);
      }
      if (take_candidate(h, bt, ray, filter, cc, best, tmax) && any_hit) {
        triangle_tests += static_cast<uint64_t>(l) + 1u;
        return true;
      }
    }
    triangle_tests += static_cast<uint64_t>(n);
  }
  return false;
}

/// The leaf step every search shares: the leaf's triangles in order, each
/// candidate through the tie rule and the filter; an accepted one becomes the
/// best and shortens the interval. Returns true when an any-hit search is done.
/// With `lanes` (the tree's TriangleLanes, or nullptr) and a tester that has a
/// four-lane form, four triangles are tested at once (search_leaf_lanes), with
/// the same answers and counts.
template <class Tester>
__attribute__((always_inline)) inline bool search_leaf(const BvhTriangle* tris, const TriangleLanes* lanes,
                                                       BvhRef leaf, const Tester& tester, const Ray& ray,
                                                       const CandidateFilter& filter, CandidateCounters& cc,
                                                       bool any_hit, Hit& best, float& tmax,
                                                       uint64_t& triangle_tests) {
  if constexpr (HasLaneForm<Tester>::value)
    if (lanes != nullptr)
      return search_leaf_lanes(tris, *lanes, leaf, tester, ray, filter, cc, any_hit, best, tmax, triangle_tests);
  for (uint32_t i = leaf.index, end = leaf.index + leaf.count; i < end; ++i) {
    const BvhTriangle& bt = tris[i];
    ++triangle_tests;
    Hit h;
    if (!tester.intersect(bt.tri, candidate_limit(best, tmax), h)) continue;
    if (take_candidate(h, bt, ray, filter, cc, best, tmax) && any_hit) return true;
  }
  return false;
}

/// Pops the next subtree the ray can still reach before its closest hit into
/// `ref`; false when the stack is empty (the search is over).
template <class Entry>
__attribute__((always_inline)) inline bool pop_reachable(const Entry* stack, int& sp, float tmax, BvhRef& ref) {
  do {
    if (sp == 0) return false;
    --sp;
  } while (stack[sp].t > cull_limit(tmax));
  ref = BvhRef{stack[sp].index, stack[sp].count};
  return true;
}

}  // namespace vbsim
