// Closest-hit (and any-hit) search over a 4- or 8-wide BVH (Bvh::nodes4 /
// nodes8): one node fetch gives every child slot's box, all tested at once
// (RayBoxTester's wide test); the met children are visited nearest first: the
// nearest is descended into and the others pushed, farthest first, so the
// next nearest is popped next. Ties on the entry distance go to the lower
// slot. Leaves, candidate filtering, ties between hits and culling are those
// of the binary search (search_rules.h), so the hit is the same whatever the
// width.
#pragma once
#include <cstdint>

#include "datapath/candidate_filter.h"
#include "datapath/hit.h"
#include "datapath/ray.h"
#include "datapath/ray_box_tester.h"
#include "datapath/search_rules.h"
#include "scene/bvh.h"

namespace vbsim {

/// The slots whose bit is set in `met`, nearest entry first (ties: lower slot
/// first), into `order`; returns how many.
inline int wide_visit_order(unsigned met, const float* entry, int* order) {
  int n = 0;
  while (met != 0u) {
    const int c = __builtin_ctz(met);
    met &= met - 1u;
    int k = n++;
    for (; k > 0 && entry[order[k - 1]] > entry[c]; --k) order[k] = order[k - 1];  // stable: equal stays after
    order[k] = c;
  }
  return n;
}

/// The wide node array of `bvh` for width W.
template <int W>
const std::vector<WideBvhNode<W>>& wide_nodes(const Bvh& bvh);
template <>
inline const std::vector<BvhNode4>& wide_nodes<4>(const Bvh& bvh) { return bvh.nodes4; }
template <>
inline const std::vector<BvhNode8>& wide_nodes<8>(const Bvh& bvh) { return bvh.nodes8; }

/// Asks the host cache for a pushed child's node (both lines of a 4-wide
/// node, the first two of an 8-wide one) while the search goes down the
/// nearer child: a host-speed hint, no part of the model. For a leaf it asks
/// for the root's node, which is cached anyway, so that no branch is needed.
template <int W>
__attribute__((always_inline)) inline void prefetch_node(const WideBvhNode<W>* nodes, uint32_t index,
                                                         uint32_t count) {
  const char* const p = reinterpret_cast<const char*>(nodes + (count != 0u ? 0u : index));
  __builtin_prefetch(p);
  __builtin_prefetch(p + 64);
}

/// The box test of a wide search: RayBoxTester's SSE2 (or scalar) form.
struct PortableWideBoxes {
  template <int W>
  static unsigned hits(const RayBoxTester& box, const WideBvhNode<W>& n, float tmax, float* entry) {
    return box.hits(n, tmax, entry);
  }
};

/// The search itself, whatever the box test; inlined into each entry point
/// below, so that the AVX2 one is compiled for AVX2 throughout.
template <int W, class Tester, class Boxes>
__attribute__((always_inline)) inline Hit wide_search(const Bvh& bvh, const Ray& ray, const CandidateFilter& filter,
                                                      CandidateCounters& cc, TraversalCounters& tc, bool any_hit) {
  Hit best;
  if (bvh.tris.empty()) return best;
  const Tester tester(ray);
  const RayBoxTester box(ray);
  float tmax = ray.tmax;
  struct Entry {
    uint32_t index, count;
    float t;
  } stack[kTraversalStackDepth];
  int sp = 0;
  uint64_t node_visits = 0, box_tests = 1, triangle_tests = 0, pushes = 0;
  const auto finish = [&] {
    tc.node_visits += node_visits;
    tc.box_tests += box_tests;
    tc.triangle_tests += triangle_tests;
    tc.stack_pushes += pushes;
    tc.stack_pops += pushes - static_cast<uint64_t>(sp);
    return best;
  };
#if defined(__SSE2__)
  if (!box.hits_sse2(bvh.root_bounds, cull_limit(tmax))) return finish();
#else
  if (!box.hits(bvh.root_bounds, cull_limit(tmax))) return finish();
#endif
  const WideBvhNode<W>* const nodes = wide_nodes<W>(bvh).data();
  const BvhTriangle* const tris = bvh.tris.data();
  const TriangleLanes* const lanes = bvh.triangle_lanes();
  BvhRef ref = bvh.root;
  for (;;) {
    if (!ref.is_leaf()) {
      const WideBvhNode<W>& n = nodes[ref.index];
      ++node_visits;
      box_tests += n.children;
      alignas(16) float entry[W];
      const unsigned met = Boxes::template hits<W>(box, n, cull_limit(tmax), entry);
      if (met != 0u) {
        const unsigned rest = met & (met - 1u);
        if (rest == 0u) {  // one child met: no ordering
          ref = n.child(__builtin_ctz(met));
          continue;
        }
        if ((rest & (rest - 1u)) == 0u) {  // two met (the commonest case after one): one comparison
          const int a = __builtin_ctz(met), b = __builtin_ctz(rest);  // a < b: a wins a tie
          const int near = entry[b] < entry[a] ? b : a, far = a + b - near;
          stack[sp++] = {n.ref[far], n.count[far], entry[far]};
          prefetch_node(nodes, n.ref[far], n.count[far]);
          ++pushes;
          ref = n.child(near);
          continue;
        }
        int order[W];
        const int k = wide_visit_order(met, entry, order);
        for (int i = k - 1; i >= 1; --i) {
          stack[sp++] = {n.ref[order[i]], n.count[order[i]], entry[order[i]]};
          prefetch_node(nodes, n.ref[order[i]], n.count[order[i]]);
        }
        pushes += static_cast<uint64_t>(k - 1);
        ref = n.child(order[0]);
        continue;
      }
    } else if (search_leaf(tris, lanes, ref, tester, ray, filter, cc, any_hit, best, tmax, triangle_tests)) {
      return finish();
    }
    if (!pop_reachable(stack, sp, tmax, ref)) return finish();
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
/// The 8-wide box test in one AVX2 vector (RayBoxTester::hits_avx2).
struct Avx2WideBoxes {
  template <int W>
  __attribute__((target("avx2"))) static unsigned hits(const RayBoxTester& box,
                                                                        const WideBvhNode<W>& n, float tmax,
                                                                        float* entry) {
    static_assert(W == 8, "the AVX2 test is 8 wide");
    return box.hits_avx2(n, tmax, entry);
  }
};

template <class Tester>
__attribute__((target("avx2"), noinline)) Hit wide_closest_hit_avx2(const Bvh& bvh, const Ray& ray,
                                                                     const CandidateFilter& filter,
                                                                     CandidateCounters& cc, TraversalCounters& tc,
                                                                     bool any_hit) {
  return wide_search<8, Tester, Avx2WideBoxes>(bvh, ray, filter, cc, tc, any_hit);
}
#endif

/// closest_hit() over the W-wide tree (precondition: bvh.width == W): 8 wide
/// on an AVX2 host with the AVX2 box test (the same answers), else SSE2.
template <int W, class Tester>
Hit wide_closest_hit(const Bvh& bvh, const Ray& ray, const CandidateFilter& filter, CandidateCounters& cc,
                     TraversalCounters& tc, bool any_hit) {
#if defined(__x86_64__) && defined(__GNUC__)
  if constexpr (W == 8)
    if (host_has_avx2()) return wide_closest_hit_avx2<Tester>(bvh, ray, filter, cc, tc, any_hit);
#endif
  return wide_search<W, Tester, PortableWideBoxes>(bvh, ray, filter, cc, tc, any_hit);
}

}  // namespace vbsim
