// Closest-hit (and any-hit) search over the project's BVH: the BVH stepping of
// the datapath. Nearer child box first; a candidate the
// filter rejects does not shorten the interval. Box tests are the robust slab
// test (Ize 2013): the far distance is widened by 1 + 2 gamma(3) so that float
// rounding never culls a box the ray touches.
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

/// Per-ray slab-test set-up: reciprocal direction and, per axis, which of the
/// node's six bounds the ray meets first. A zero direction component is replaced
/// by +-1e-18 (as Embree does), so no slab distance is ever NaN.
struct RayBoxTester {
  float ox, oy, oz, ix, iy, iz;
  int nx, ny, nz;  ///< index of the near bound among (lo[0..2], hi[0..2])

  static float safe_reciprocal(float d) {
    constexpr float tiny = 1e-18f;
    return 1.0f / (std::fabs(d) < tiny ? std::copysign(tiny, d) : d);
  }
  explicit RayBoxTester(const Ray& ray)
      : ox(ray.o.x), oy(ray.o.y), oz(ray.o.z), ix(safe_reciprocal(ray.d.x)),
        iy(safe_reciprocal(ray.d.y)), iz(safe_reciprocal(ray.d.z)), nx(ix >= 0 ? 0 : 3),
        ny(iy >= 0 ? 1 : 4), nz(iz >= 0 ? 2 : 5) {}

  /// True when the ray's interval [tmin, tmax] meets the node's box; `entry` is
  /// then the distance where it enters the box (clamped to tmin).
  bool hits(const BvhNode& n, float tmin, float tmax, float& entry) const {
    constexpr float widen = 1.0f + 2.0f * (3.0f * 5.9604645e-8f) / (1.0f - 3.0f * 5.9604645e-8f);
    // The node starts with its six bounds as consecutive floats (bvh.h layout).
    const float* b = reinterpret_cast<const float*>(&n);
    const float tnx = (b[nx] - ox) * ix, tfx = (b[3 - nx] - ox) * ix;
    const float tny = (b[ny] - oy) * iy, tfy = (b[5 - ny] - oy) * iy;
    const float tnz = (b[nz] - oz) * iz, tfz = (b[7 - nz] - oz) * iz;
    const float tn = std::max(std::max(tnx, tny), std::max(tnz, tmin));
    const float tf = std::min(std::min(tfx, tfy), tfz) * widen;
    entry = tn;
    return tn <= std::min(tf, tmax);
  }
};
static_assert(offsetof(BvhNode, lo) == 0 && offsetof(BvhNode, hi) == 3 * sizeof(float),
              "the box test reads a node's bounds as six consecutive floats");

/// Closest accepted hit of `ray` (any accepted hit when `any_hit`); miss: prim -1.
/// Both children's boxes are tested at an interior node; the nearer is visited
/// first and the farther is skipped later if a hit has come closer than its entry.
template <class Tester>
Hit closest_hit(const Bvh& bvh, const Ray& ray, const CandidateFilter& filter,
                CandidateCounters& cc, TraversalCounters& tc, bool any_hit = false) {
  Hit best;
  if (bvh.tris.empty()) return best;  // an empty scene: its single leaf holds nothing
  const Tester tester(ray);
  const RayBoxTester box(ray);
  float tmax = ray.tmax;
  struct Entry {
    uint32_t node;
    float t;
  } stack[kTraversalStackDepth];
  int sp = 0;
  // Counted locally and added once: the search's inner loop stays in registers.
  uint64_t box_tests = 1, triangle_tests = 0;
  const auto finish = [&] {
    tc.box_tests += box_tests;
    tc.node_visits += box_tests;  // every box test fetches one node
    tc.triangle_tests += triangle_tests;
    return best;
  };
  float entry;
  if (!box.hits(bvh.nodes[0], ray.tmin, tmax, entry)) return finish();
  uint32_t node = 0;
  for (;;) {
    const BvhNode& n = bvh.nodes[node];
    if (!n.is_leaf()) {
      const uint32_t a = node + 1, b = n.offset;
      float ta, tb;
      box_tests += 2;
      const bool ha = box.hits(bvh.nodes[a], ray.tmin, tmax, ta);
      const bool hb = box.hits(bvh.nodes[b], ray.tmin, tmax, tb);
      if (ha & hb) {
        // Branch-free order: push the farther child, descend into the nearer.
        const bool a_first = ta <= tb;
        stack[sp].node = a_first ? b : a;
        stack[sp].t = a_first ? tb : ta;
        ++sp;
        node = a_first ? a : b;
        continue;
      }
      if (ha | hb) {
        node = ha ? a : b;
        continue;
      }
    } else {
      for (uint32_t i = n.offset, end = n.offset + n.count(); i < end; ++i) {
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
    node = stack[sp].node;
  }
}

}  // namespace vbsim
