// Nodes 4 and 8 wide (scene/bvh_collapse.h, datapath/wide_closest_hit.h): a
// collapse and a search worked by hand, the layout promises of the wide
// nodes on the bunny, the wide box test (scalar, SSE2 and, on an AVX2 host,
// AVX2) against the one-box test it must equal, and the same hits as the
// binary search on every ray.
#include <catch2/catch.hpp>

#include <cstring>
#include <random>
#include <vector>

#include "bench/functional_bench.h"
#include "datapath/closest_hit.h"
#include "datapath/testers.h"
#include "datapath/wide_closest_hit.h"
#include "scene/bvh.h"
#include "scene/bvh_collapse.h"
#include "scene/bvh_stats.h"
#include "bvh_checks.h"

using namespace vbsim;

namespace {

/// Four triangles across the x axis at x = 1, 2, 3, 4 (y, z in [-1, 1]).
Scene four_walls() {
  std::vector<Triangle> tris;
  for (int k = 1; k <= 4; ++k) {
    const float x = static_cast<float>(k);
    tris.push_back({{x, -1, -1}, {x, 1, -1}, {x, -1, 1}});
  }
  return make_scene(std::move(tris));
}

Bvh walls_bvh(int width) {
  BvhBuildOptions o;
  o.builder = BvhBuilder::SweepSah;
  o.max_leaf_size = 1;
  o.width = width;
  return build_bvh(four_walls(), o);
}

/// Walks the W-wide tree: pre-order indices, slot boxes that are exactly their
/// triangles' bounds, leaves in the binary tree's order; returns the depth.
template <int W>
int check_wide(const Bvh& bvh, BvhRef ref, const Bounds3f& box, uint32_t& next_node, uint32_t& next_tri,
               uint64_t& opened) {
  if (ref.is_leaf()) {
    CHECK(ref.index == next_tri);
    next_tri += ref.count;
    Bounds3f exact;
    for (uint32_t i = ref.index; i < ref.index + ref.count; ++i) {
      exact.extend(bvh.tris[i].tri.v0);
      exact.extend(bvh.tris[i].tri.v1);
      exact.extend(bvh.tris[i].tri.v2);
    }
    CHECK(test::same_box(box, exact));
    return 1;
  }
  CHECK(ref.index == next_node);
  REQUIRE(ref.index < wide_nodes<W>(bvh).size());
  ++next_node;
  const WideBvhNode<W>& n = wide_nodes<W>(bvh)[ref.index];
  REQUIRE(n.children >= 2);
  REQUIRE(n.children <= static_cast<uint32_t>(W));
  opened += n.children - 1;  // a node of k slots stands for k - 1 binary nodes
  Bounds3f all;
  int depth = 0;
  for (int c = 0; c < static_cast<int>(n.children); ++c) {
    const Bounds3f b = n.child_bounds(c);
    all.extend(b.lo);
    all.extend(b.hi);
    depth = std::max(depth, check_wide<W>(bvh, n.child(c), b, next_node, next_tri, opened));
  }
  CHECK(test::same_box(box, all));
  for (int c = static_cast<int>(n.children); c < W; ++c) {  // unused slots: inverted boxes, null references
    CHECK(n.box[0][0][c] == INFINITY);
    CHECK(n.box[0][1][c] == -INFINITY);
    CHECK(n.child(c).index == 0);
    CHECK(n.child(c).count == 0);
  }
  return 1 + depth;
}

template <int W>
void check_wide_structure(const Bvh& bvh) {
  uint32_t next_node = 0, next_tri = 0;
  uint64_t opened = 0;
  const int depth = check_wide<W>(bvh, bvh.root, bvh.root_bounds, next_node, next_tri, opened);
  CHECK(depth == bvh.wide_depth);
  CHECK(next_node == wide_nodes<W>(bvh).size());
  CHECK(next_tri == bvh.tris.size());
  CHECK(opened == bvh.nodes.size());  // every binary node opened exactly once
  CHECK(reinterpret_cast<uintptr_t>(wide_nodes<W>(bvh).data()) % 64 == 0);
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("four walls collapse into one node of four leaves, searched as worked by hand", "[bvh][wide]") {
  // Binary (leaf size 1): the SAH splits 2 | 2 (areas 16 + 16 against 8 + 3 x 24
  // for 1 | 3), so node 0 holds {walls 1, 2} and {walls 3, 4}.
  const Bvh two = walls_bvh(2);
  REQUIRE(two.nodes.size() == 3);
  for (int width : {4, 8}) {
    INFO("width " << width);
    const Bvh b = walls_bvh(width);
    CHECK(b.width == width);
    CHECK(b.nodes.size() == 3);  // the binary tree is kept
    CHECK(b.wide_depth == 2);
    CHECK(b.depth == 3);
    CHECK(b.traversal_nodes() == 1);
    // Both halves opened (equal areas: the first one first), walls in x order.
    const auto slot = [&](int c) { return width == 4 ? b.nodes4[0].child(c) : b.nodes8[0].child(c); };
    const auto box = [&](int c) { return width == 4 ? b.nodes4[0].child_bounds(c) : b.nodes8[0].child_bounds(c); };
    CHECK((width == 4 ? b.nodes4[0].children : b.nodes8[0].children) == 4);
    for (int c = 0; c < 4; ++c) {
      CHECK(slot(c).count == 1);
      CHECK(slot(c).index == static_cast<uint32_t>(c));
      CHECK(box(c).lo.x == static_cast<float>(c + 1));
      CHECK(box(c).hi.x == static_cast<float>(c + 1));
    }
  }
  // A ray along +x from the origin meets every wall's box. Binary: the root box,
  // 2 boxes at node 0 and 2 at node 1 (5 tests, 2 fetches, 2 pushes), wall 1 at
  // t = 1, then both pushed entries (t 2 and 3) popped and culled. Wide: the
  // root box and 4 boxes in one fetch, 3 pushes (walls 4, 3, 2 in that order),
  // wall 1, then the 3 entries popped and culled.
  Ray ray;
  ray.o = {0, -0.25f, -0.25f};  // inside every wall (y + z < 0)
  ray.d = {1, 0, 0};
  const CandidateFilter filter(SelfIntersectionMethod{});
  for (int width : {2, 4, 8}) {
    INFO("width " << width);
    const Bvh b = walls_bvh(width);
    CandidateCounters cc;
    TraversalCounters tc;
    const Hit h = closest_hit<ThreeHalfPlaneTester>(b, ray, filter, cc, tc);
    CHECK(h.prim == 0);
    CHECK(h.t == 1.0f);
    CHECK(tc.node_visits == (width == 2 ? 2u : 1u));
    CHECK(tc.box_tests == 5u);
    CHECK(tc.triangle_tests == 1u);
    CHECK(tc.stack_pushes == (width == 2 ? 2u : 3u));
    CHECK(tc.stack_pops == tc.stack_pushes);
  }
}

TEST_CASE("wide trees of the bunny keep the layout's promises", "[bvh][wide]") {
  const Scene bunny = load_scene(test::kBunnyPath);
  for (int leaf : {1, 4, 16}) {
    INFO("leaf " << leaf);
    BvhBuildOptions o;
    o.max_leaf_size = leaf;
    o.width = 4;
    const Bvh b4 = build_bvh(bunny, o);
    test::check_structure(bunny, b4, leaf);  // the binary tree underneath is untouched
    check_wide_structure<4>(b4);
    o.width = 8;
    const Bvh b8 = build_bvh(bunny, o);
    check_wide_structure<8>(b8);
    CHECK(b8.nodes8.size() < b4.nodes4.size());
    const BvhStats s4 = compute_bvh_stats(b4), s8 = compute_bvh_stats(b8);
    CHECK(s4.wide_nodes == static_cast<int64_t>(b4.nodes4.size()));
    CHECK(s4.wide_node_bytes == 128 * s4.wide_nodes);
    CHECK(s8.wide_node_bytes == 256 * static_cast<int64_t>(b8.nodes8.size()));
    CHECK(s8.wide_depth == b8.wide_depth);
    CHECK(s4.nodes == static_cast<int64_t>(b4.nodes.size()));
    CHECK(b4.nodes4.size() < b4.nodes.size());
  }
  BvhBuildOptions bad;
  bad.width = 3;
  CHECK_THROWS_AS(build_bvh(bunny, bad), std::invalid_argument);
  bad.width = 4;
  bad.low_precision.enabled = true;
  CHECK_THROWS_AS(build_bvh(bunny, bad), std::invalid_argument);
}

TEST_CASE("the wide box test answers as the one-box test does, slot by slot", "[bvh][wide][box]") {
  const Scene bunny = load_scene(test::kBunnyPath);
  BvhBuildOptions o;
  o.width = 8;
  const Bvh b = build_bvh(bunny, o);
  const std::vector<TraceRay> rays = bench_rays(bunny, 400, 11);
  std::mt19937 rng(5);
  uint64_t met = 0, tested = 0;
  for (const TraceRay& tr : rays) {
    Ray ray;
    ray.o = tr.o;
    ray.d = tr.d;
    const RayBoxTester box(ray);
    for (size_t k = 0; k < b.nodes8.size(); k += 1 + rng() % 7) {
      const BvhNode8& n = b.nodes8[k];
      const float tmax = (rng() % 3 == 0) ? 2.0f : INFINITY;
      alignas(16) float entry[8], scalar_entry[8];
      const unsigned mask = box.hits(n, tmax, entry);
      CHECK(mask == box.hits_wide_scalar(n, tmax, scalar_entry));
#if defined(__x86_64__) && defined(__GNUC__)
      if (host_has_avx2()) {  // the 8-wide search's AVX2 form: the same bits
        alignas(32) float avx_entry[8];
        CHECK(box.hits_avx2(n, tmax, avx_entry) == mask);
        for (int c = 0; c < static_cast<int>(n.children); ++c) CHECK(same_bits(avx_entry[c], entry[c]));
      }
#endif
      for (int c = 0; c < static_cast<int>(n.children); ++c) {
        const bool one = box.hits(n.child_bounds(c), tmax);
        CHECK(((mask >> c) & 1u) == (one ? 1u : 0u));
        CHECK(same_bits(entry[c], scalar_entry[c]));
        ++tested;
        met += one;
      }
      CHECK((mask >> n.children) == 0u);
    }
  }
  CHECK(met > 1000);  // the comparison covered met boxes, not only misses (of ~275,000 slots)
}

namespace {

/// The vector forms' masks against the scalar form's (which masks slots >=
/// children off) for nodes of 1 .. W used slots, every unused slot cleared:
/// origins inside, outside, far away and infinite, directions with zero,
/// negative zero and tiny components, every tmin / tmax pair below.
template <int W>
void check_unused_slots_never_met() {
  const float inf = INFINITY;
  const float origins[] = {0.0f, 0.5f, -2.0f, 3e30f, -inf};
  const float directions[] = {1.0f, -3.0f, 0.0f, -0.0f, 1e-20f};
  const float tmins[] = {0.0f, 0.5f};
  const float tmaxes[] = {inf, 1.0f, 1e-3f};
  uint64_t met = 0;
  for (int used = 1; used <= W; ++used) {
    WideBvhNode<W> n;
    n.clear();
    for (int c = 0; c < used; ++c) {
      const float lo = -1.0f + 0.25f * static_cast<float>(c);
      n.set_child(c, Bounds3f{{lo, lo, lo}, {lo + 1.5f, lo + 1.5f, lo + 1.5f}}, BvhRef{static_cast<uint32_t>(c), 1});
    }
    n.children = static_cast<uint32_t>(used);
    for (float ox : origins)
      for (float oy : origins)
        for (float dx : directions)
          for (float dy : directions)
            for (float dz : directions)
              for (float tmin : tmins)
                for (float tmax : tmaxes) {
                  Ray ray;
                  ray.o = {ox, oy, 0.25f};
                  ray.d = {dx, dy, dz};
                  ray.tmin = tmin;
                  const RayBoxTester box(ray);
                  alignas(32) float entry[W], scalar_entry[W];
                  const unsigned mask = box.hits(n, tmax, entry);
                  CHECK((mask >> used) == 0u);
                  CHECK(mask == box.hits_wide_scalar(n, tmax, scalar_entry));
#if defined(__x86_64__) && defined(__GNUC__)
                  if constexpr (W == 8)
                    if (host_has_avx2()) CHECK(box.hits_avx2(n, tmax, entry) == mask);
#endif
                  met += static_cast<unsigned>(__builtin_popcount(mask));
                }
  }
  CHECK(met > 1000);  // used slots were met too, so a mask of 0 everywhere would fail above
}

}  // namespace

TEST_CASE("an unused slot of a wide node is never met, whatever the ray", "[bvh][wide][box]") {
  check_unused_slots_never_met<4>();
  check_unused_slots_never_met<8>();
}

TEST_CASE("closest and any hits do not depend on the node width", "[bvh][wide]") {
  const Scene bunny = load_scene(test::kBunnyPath);
  Bvh trees[3];
  int k = 0;
  for (int width : {2, 4, 8}) {
    BvhBuildOptions o;
    o.width = width;
    trees[k++] = build_bvh(bunny, o);
  }
  const std::vector<TraceRay> rays = bench_rays(bunny, 4000, 3);
  const CandidateFilter filter(SelfIntersectionMethod{});
  uint64_t hits = 0, fetches[3] = {0, 0, 0};
  for (const TraceRay& tr : rays) {
    Ray ray;
    ray.o = tr.o;
    ray.d = tr.d;
    for (bool any : {false, true}) {
      CandidateCounters cc[3];
      TraversalCounters tc[3];
      Hit h[3];
      for (int i = 0; i < 3; ++i) h[i] = closest_hit<ThreeHalfPlaneTester>(trees[i], ray, filter, cc[i], tc[i], any);
      for (int i = 1; i < 3; ++i) {
        if (any) {  // the first hit found depends on the order; whether there is one does not
          REQUIRE((h[i].prim >= 0) == (h[0].prim >= 0));
          continue;
        }
        REQUIRE(h[i].prim == h[0].prim);
        REQUIRE(same_bits(h[i].t, h[0].t));
        REQUIRE(same_bits(h[i].u, h[0].u));
        REQUIRE(same_bits(h[i].v, h[0].v));
        REQUIRE(h[i].front == h[0].front);
      }
      for (int i = 0; i < 3 && !any; ++i) fetches[i] += tc[i].node_visits;
      hits += !any && h[0].prim >= 0;
    }
  }
  CHECK(hits > 1000);
  CHECK(fetches[1] < fetches[0] * 2 / 3);  // wider nodes: fewer fetches
  CHECK(fetches[2] < fetches[1]);
}
