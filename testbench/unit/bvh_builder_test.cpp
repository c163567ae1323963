// Tests of build_bvh, EmbreeReference and bvh_stats: structural invariants of
// the layout in bvh.h, and closest hits through the BVH cross-checked against
// a brute-force double-precision search and against Embree's own intersector.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/bvh.h"
#include "scene/bvh_stats.h"
#include "scene/embree_reference.h"
#include "scene/scene.h"
#include "bvh_checks.h"

using namespace vbsim;
using namespace vbsim::test;

TEST_CASE("bunny BVH: every triangle in one leaf, bounds nested and tight", "[bvh]") {
  const Scene bunny = load_scene(kBunnyPath);
  for (int max_leaf : {1, 4, 8}) {
    CAPTURE(max_leaf);
    const Bvh bvh = build_bvh(bunny, {max_leaf});
    check_structure(bunny, bvh, max_leaf);
  }
}

TEST_CASE("random soup BVHs satisfy the layout contract", "[bvh]") {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const Scene soup = random_soup(seed, 400);
    for (int max_leaf : {1, 2, 5, 16}) {
      CAPTURE(seed, max_leaf);
      check_structure(soup, build_bvh(soup, {max_leaf}), max_leaf);
    }
  }
}

TEST_CASE("tiny scenes: one triangle is a root leaf, an empty scene has no triangles", "[bvh]") {
  const Scene one = make_scene({Triangle{{0, 0, 0}, {1, 0, 0}, {0, 2, 3}}});
  const Bvh single = build_bvh(one);
  CHECK(single.nodes.empty());  // the root leaf is no node record
  CHECK(single.root.is_leaf());
  CHECK(single.root.index == 0);
  CHECK(single.root.count == 1);
  CHECK(single.depth == 1);
  CHECK(single.tris.size() == 1);
  CHECK(single.root_bounds.hi == Vec3f{1, 2, 3});
  CHECK(single.root_bounds.lo == Vec3f{0, 0, 0});
  check_structure(one, single, 4);

  // Three triangles, leaves of up to 4: still one leaf, holding all three.
  const Scene three = make_scene({Triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, Triangle{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}},
                                  Triangle{{0, 0, 2}, {1, 0, 2}, {0, 1, 2}}});
  const Bvh few = build_bvh(three, {4});
  check_structure(three, few, 4);
  const Bvh split = build_bvh(three, {1});  // leaves of one: two node records
  CHECK(split.nodes.size() == 2);
  CHECK(split.depth == 3);
  check_structure(three, split, 1);

  const Bvh empty = build_bvh(make_scene({}));
  CHECK(empty.nodes.empty());
  CHECK(empty.tris.empty());
  CHECK(empty.depth == 0);
  CHECK(empty.root_bounds.lo.x > empty.root_bounds.hi.x);  // inverted: no ray can enter it

  CHECK_THROWS_AS(build_bvh(one, {0}), std::invalid_argument);
  CHECK_THROWS_AS(build_bvh(one, {70000}), std::invalid_argument);
}

TEST_CASE("BVH builds are reproducible byte for byte", "[bvh]") {
  const Scene soup = random_soup(7, 3000);
  const Bvh a = build_bvh(soup), b = build_bvh(soup);
  REQUIRE(a.nodes.size() == b.nodes.size());
  REQUIRE(a.tris.size() == b.tris.size());
  REQUIRE(!a.nodes.empty());
  CHECK(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode)) == 0);
  CHECK((same_box(a.root_bounds, b.root_bounds) && a.root.index == b.root.index && a.root.count == b.root.count));
  CHECK(std::memcmp(a.tris.data(), b.tris.data(), a.tris.size() * sizeof(BvhTriangle)) == 0);
}

TEST_CASE("closest hits through the bunny BVH agree with brute force and Embree", "[bvh]") {
  const Scene bunny = load_scene(kBunnyPath);
  const Bvh bvh = build_bvh(bunny);
  const EmbreeReference embree(bunny);
  int hits = 0;
  const int compared = cross_check(bunny, bvh, embree, 11, 600, hits);
  CHECK(compared > 500);  // most random rays are well conditioned
  CHECK(hits > 100);      // and many of them hit the bunny
}

TEST_CASE("closest hits through random soup BVHs agree with brute force and Embree", "[bvh]") {
  for (uint32_t seed : {21u, 22u}) {
    const Scene soup = random_soup(seed, 300);
    const Bvh bvh = build_bvh(soup, {3});
    const EmbreeReference embree(soup);
    int hits = 0;
    const int compared = cross_check(soup, bvh, embree, seed, 800, hits);
    CHECK(compared > 600);
    CHECK(hits > 200);
  }
}

TEST_CASE("EmbreeReference of an empty scene misses", "[bvh]") {
  const EmbreeReference embree(make_scene({}));
  int32_t prim = 7;
  float t = 0, u = 0, v = 0;
  CHECK_FALSE(embree.intersect({0, 0, 0}, {1, 0, 0}, 0, INFINITY, prim, t, u, v));
  CHECK(prim == 7);
}

TEST_CASE("bvh_stats of two separate triangles match a hand count", "[bvh]") {
  // Flat boxes [0,1]x[0,1]x{0} and [9,10]x[0,1]x{0}: area 2 each, root area 20.
  const Scene two = make_scene({Triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, Triangle{{9, 0, 0}, {10, 0, 0}, {10, 1, 0}}});
  const BvhStats s = compute_bvh_stats(build_bvh(two, {1}));
  CHECK(s.nodes == 1);  // one record holds both leaves
  CHECK(s.leaves == 2);
  CHECK(s.triangles == 2);
  CHECK(s.average_leaf_size == 1.0);
  CHECK(s.max_leaf_size == 1);
  CHECK(s.depth == 2);
  CHECK(s.node_bytes == 64);
  CHECK(s.triangle_bytes == 80);
  CHECK(s.sah_cost == Approx(1.0 + 2.0 / 20 + 2.0 / 20));

  // A root leaf: no node records, one leaf at weight 1.
  const BvhStats one = compute_bvh_stats(build_bvh(make_scene({two.triangles[0]})));
  CHECK(one.nodes == 0);
  CHECK(one.node_bytes == 0);
  CHECK(one.leaves == 1);
  CHECK(one.depth == 1);
  CHECK(one.max_leaf_size == 1);
  CHECK(one.sah_cost == Approx(1.0));
  const BvhStats none = compute_bvh_stats(build_bvh(make_scene({})));
  CHECK((none.nodes == 0 && none.leaves == 0 && none.depth == 0 && none.triangles == 0));
}

TEST_CASE("bvh_stats of the bunny are consistent with its tree", "[bvh]") {
  const Bvh bvh = build_bvh(load_scene(kBunnyPath));
  const BvhStats s = compute_bvh_stats(bvh);
  CHECK(s.nodes == s.leaves - 1);  // binary tree: interior nodes = leaves - 1
  CHECK(s.triangles == 3674);
  CHECK(s.average_leaf_size * s.leaves == Approx(3674));
  CHECK(s.max_leaf_size <= 4);
  CHECK(s.depth == bvh.depth);
  CHECK(s.node_bytes == 64 * s.nodes);
  CHECK(s.sah_cost > 1.0);
  CHECK(format_bvh_stats(s).find("SAH cost") != std::string::npos);
}

TEST_CASE("BVH build options: Embree's qualities, leaf sizes and traversal costs give other valid trees",
          "[bvh][bvh-options]") {
  const Scene bunny = load_scene(kBunnyPath);
  const BvhStats reference = compute_bvh_stats(build_bvh(bunny));
  int other_shapes = 0;
  for (const BvhQuality q : {BvhQuality::Low, BvhQuality::Medium, BvhQuality::High})
    for (const int leaf : {1, 4, 16, 32})
      for (const float cost : {1.0f, 8.0f}) {
        INFO(bvh_quality_name(q) << ", leaves up to " << leaf << ", traversal cost " << cost);
        BvhBuildOptions o;
        o.quality = q;
        o.max_leaf_size = leaf;
        o.traversal_cost = cost;
        const Bvh bvh = build_bvh(bunny, o);
        check_structure(bunny, bvh, leaf);  // every triangle once, boxes exact, leaves within the limit
        const BvhStats s = compute_bvh_stats(bvh);
        other_shapes += s.nodes != reference.nodes || s.depth != reference.depth;
        if (leaf == 1) CHECK(s.max_leaf_size == 1);
      }
  CHECK(other_shapes >= 10);
  // A higher traversal cost makes larger leaves (SAH), up to the limit.
  BvhBuildOptions cheap, dear;
  cheap.max_leaf_size = dear.max_leaf_size = 16;
  dear.traversal_cost = 8;
  CHECK(compute_bvh_stats(build_bvh(bunny, dear)).average_leaf_size >
        2 * compute_bvh_stats(build_bvh(bunny, cheap)).average_leaf_size);
  // Triangles priced four at a time (Embree's Triangle4 pricing): fuller
  // leaves and fewer nodes, with either builder; still a valid tree.
  for (const BvhBuilder builder : {BvhBuilder::Embree, BvhBuilder::SweepSah}) {
    INFO(bvh_builder_name(builder));
    BvhBuildOptions one, four;
    one.builder = four.builder = builder;
    four.sah_block_size = 4;
    one.max_leaf_size = four.max_leaf_size = 8;
    const Bvh blocks = build_bvh(bunny, four);
    check_structure(bunny, blocks, 8);
    const BvhStats s1 = compute_bvh_stats(build_bvh(bunny, one)), s4 = compute_bvh_stats(blocks);
    CHECK(s4.average_leaf_size > 1.5 * s1.average_leaf_size);
    CHECK(s4.nodes < s1.nodes);
  }
  BvhBuildOptions bad;
  for (const int block : {0, 3, 32, -4}) {
    bad.sah_block_size = block;
    CHECK_THROWS_WITH(build_bvh(bunny, bad), Catch::Contains("sah_block_size"));
  }
  bad = {};
  bad.max_leaf_size = 33;
  CHECK_THROWS_AS(build_bvh(bunny, bad), std::invalid_argument);
  bad = {};
  bad.traversal_cost = 0;
  CHECK_THROWS_AS(build_bvh(bunny, bad), std::invalid_argument);
  BvhQuality q;
  CHECK(parse_bvh_quality("medium", q));
  CHECK(q == BvhQuality::Medium);
  CHECK_FALSE(parse_bvh_quality("best", q));
}
