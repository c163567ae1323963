// Closest-hit (and any-hit) search over the project's BVH: the BVH stepping of
// the datapath. One node fetch gives both children's boxes (bvh.h); the nearer
// child is visited first; a candidate the filter rejects does not shorten the
// interval. Box tests are the robust slab test (Ize 2013): the far distance is
// widened by 1 + 2 gamma(3) so that float rounding never culls a box the ray touches.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "datapath/candidate_filter.h"
#include "datapath/hit.h"
#include "datapath/ray.h"
#include "scene/bvh.h"

namespace vbsim {

/// Work one search did, for cost accounting.
struct TraversalCounters {
  uint64_t node_visits = 0;     ///< BvhNode fetches: one per interior node visited
  uint64_t box_tests = 0;       ///< the root's box, then both child boxes of every node fetched
  uint64_t triangle_tests = 0;  ///< triangles handed to the tester
  void add(const TraversalCounters& o) {
    node_visits += o.node_visits;
    box_tests += o.box_tests;
    triangle_tests += o.triangle_tests;
  }
};

constexpr int kTraversalStackDepth = 128;

/// Throws std::runtime_error when `bvh` is deeper than the traversal stack. A
/// search holds at most one stack entry per node fetched on its current path,
/// so at most depth - 1 entries (Bvh::depth counts the leaf's level too).
inline void check_traversal_depth(const Bvh& bvh) {
  if (bvh.depth - 1 > kTraversalStackDepth)
    throw std::runtime_error("BVH depth exceeds the traversal stack of 128 entries");
}

/// Per-ray slab-test set-up: reciprocal direction and, per axis, which side of
/// a box (low or high bound) the ray meets first. A zero direction component is
/// replaced by +-1e-18 (as Embree does), so no slab distance is ever NaN.
struct RayBoxTester {
  float ox, oy, oz, ix, iy, iz;
  int sx, sy, sz;  ///< near side per axis: 0 (low bound) when the reciprocal is >= 0, else 1

  /// Far distances are widened by 1 + 2 gamma(3), gamma(n) = n u / (1 - n u), u = 2^-24.
  static constexpr float kWiden = 1.0f + 2.0f * (3.0f * 5.9604645e-8f) / (1.0f - 3.0f * 5.9604645e-8f);

  static float safe_reciprocal(float d) {
    constexpr float tiny = 1e-18f;
    return 1.0f / (std::fabs(d) < tiny ? std::copysign(tiny, d) : d);
  }
  explicit RayBoxTester(const Ray& ray)
      : ox(ray.o.x), oy(ray.o.y), oz(ray.o.z), ix(safe_reciprocal(ray.d.x)),
        iy(safe_reciprocal(ray.d.y)), iz(safe_reciprocal(ray.d.z)), sx(ix >= 0 ? 0 : 1),
        sy(iy >= 0 ? 0 : 1), sz(iz >= 0 ? 0 : 1) {}

  /// True when the ray's interval [tmin, tmax] meets box `b`.
  bool hits(const Bounds3f& b, float tmin, float tmax) const {
    const float tnx = ((sx ? b.hi.x : b.lo.x) - ox) * ix, tfx = ((sx ? b.lo.x : b.hi.x) - ox) * ix;
    const float tny = ((sy ? b.hi.y : b.lo.y) - oy) * iy, tfy = ((sy ? b.lo.y : b.hi.y) - oy) * iy;
    const float tnz = ((sz ? b.hi.z : b.lo.z) - oz) * iz, tfz = ((sz ? b.lo.z : b.hi.z) - oz) * iz;
    const float tn = std::max(std::max(tnx, tny), std::max(tnz, tmin));
    const float tf = std::min(std::min(tfx, tfy), tfz) * kWiden;
    return tn <= std::min(tf, tmax);
  }

  /// Tests both child boxes of `n` against [tmin, tmax]: bit c of the result is
  /// set when child c's box is met, and entry[c] is then where the ray enters it
  /// (clamped to tmin).
  unsigned hits(const BvhNode& n, float tmin, float tmax, float entry[2]) const {
    unsigned mask = 0;
    for (int c = 0; c < 2; ++c) {
      const float tnx = (n.box[0][sx][c] - ox) * ix, tfx = (n.box[0][1 - sx][c] - ox) * ix;
      const float tny = (n.box[1][sy][c] - oy) * iy, tfy = (n.box[1][1 - sy][c] - oy) * iy;
      const float tnz = (n.box[2][sz][c] - oz) * iz, tfz = (n.box[2][1 - sz][c] - oz) * iz;
      const float tn = std::max(std::max(tnx, tny), std::max(tnz, tmin));
      const float tf = std::min(std::min(tfx, tfy), tfz) * kWiden;
      entry[c] = tn;
      mask |= static_cast<unsigned>(tn <= std::min(tf, tmax)) << c;
    }
    return mask;
  }
};

/// Closest accepted hit of `ray` (any accepted hit when `any_hit`); miss: prim -1.
/// Each interior node is one fetch that tests both children's boxes; the nearer
/// child is visited first and the farther is skipped later if a hit has come
/// closer than its entry.
template <class Tester>
Hit closest_hit(const Bvh& bvh, const Ray& ray, const CandidateFilter& filter,
                CandidateCounters& cc, TraversalCounters& tc, bool any_hit = false) {
  Hit best;
  if (bvh.tris.empty()) return best;  // an empty scene: no root to read
  const Tester tester(ray);
  const RayBoxTester box(ray);
  float tmax = ray.tmax;
  struct Entry {
    BvhRef ref;
    float t;
  } stack[kTraversalStackDepth];
  int sp = 0;
  // Counted locally and added once: the search's inner loop stays in registers.
  uint64_t node_visits = 0, triangle_tests = 0;
  const auto finish = [&] {
    tc.node_visits += node_visits;
    tc.box_tests += 1 + 2 * node_visits;  // the root's box, then two per fetch
    tc.triangle_tests += triangle_tests;
    return best;
  };
  if (!box.hits(bvh.root_bounds, ray.tmin, tmax)) return finish();
  BvhRef ref = bvh.root;
  for (;;) {
    if (!ref.is_leaf()) {
      const BvhNode& n = bvh.nodes[ref.index];
      ++node_visits;
      float t[2];
      const unsigned hit = box.hits(n, ray.tmin, tmax, t);
      if (hit == 3u) {
        // Branch-free order: push the farther child, descend into the nearer.
        const int near = t[0] <= t[1] ? 0 : 1;
        stack[sp].ref = n.child(1 - near);
        stack[sp].t = t[1 - near];
        ++sp;
        ref = n.child(near);
        continue;
      }
      if (hit != 0u) {
        ref = n.child(static_cast<int>(hit >> 1));
        continue;
      }
    } else {
      for (uint32_t i = ref.index, end = ref.index + ref.count; i < end; ++i) {
        const BvhTriangle& bt = bvh.tris[i];
        ++triangle_tests;
        Hit h;
        if (!tester.intersect(bt.tri, tmax, h)) continue;
        h.prim = static_cast<int32_t>(bt.prim);
        if (!filter.accept(ray, bt.tri, h.prim, h, cc)) continue;
        best = h;
        tmax = h.t;
        if (any_hit) return finish();
      }
    }
    // Pop the next subtree that the ray can still reach before its closest hit.
    do {
      if (sp == 0) return finish();
      --sp;
    } while (stack[sp].t > tmax);
    ref = stack[sp].ref;
  }
}

}  // namespace vbsim
