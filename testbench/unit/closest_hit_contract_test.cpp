// The closest-hit search's contract on hand-built scenes: a root leaf, an empty
// scene, two stacked leaves (nearer child first, the farther culled once a hit
// is closer than its entry), a rejected candidate not shortening the interval,
// the any-hit option, the work counters, and the traversal stack bound.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "datapath/closest_hit.h"
#include "datapath/testers.h"

using namespace vbsim;

namespace {

Ray make_ray(Vec3f o, Vec3f d) {
  Ray r;
  r.o = o;
  r.d = d;
  return r;
}

struct Search {
  Hit hit;
  CandidateCounters cc;
  TraversalCounters tc;
};

Search search(const Bvh& bvh, const Ray& ray, const SelfIntersectionMethod& method = {}, bool any_hit = false) {
  Search s;
  s.hit = closest_hit<ThreeHalfPlaneTester>(bvh, ray, CandidateFilter(method), s.cc, s.tc, any_hit);
  return s;
}

// Two unit right triangles over [0,1]^2, prim 0 at z = 0 and prim 1 at z = -1.
Scene two_floors() {
  return make_scene({Triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, Triangle{{0, 0, -1}, {1, 0, -1}, {0, 1, -1}}});
}

}  // namespace

TEST_CASE("a root leaf is searched after one box test, with no node fetch", "[closest_hit]") {
  const Scene one = make_scene({Triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}});
  const Bvh bvh = build_bvh(one);
  REQUIRE(bvh.root.is_leaf());
  const Search down = search(bvh, make_ray({0.25f, 0.25f, 2}, {0, 0, -1}));
  CHECK(down.hit.prim == 0);
  CHECK(down.hit.t == 2.0f);
  CHECK(down.tc.node_visits == 0);
  CHECK(down.tc.box_tests == 1);
  CHECK(down.tc.triangle_tests == 1);
  const Search away = search(bvh, make_ray({0.25f, 0.25f, 2}, {0, 0, 1}));
  CHECK(away.hit.prim == -1);
  CHECK(away.tc.box_tests == 1);
  CHECK(away.tc.triangle_tests == 0);
}

TEST_CASE("an empty scene misses without reading the BVH", "[closest_hit]") {
  const Bvh bvh = build_bvh(make_scene({}));
  const Search s = search(bvh, make_ray({0, 0, 0}, {0, 0, 1}));
  CHECK(s.hit.prim == -1);
  CHECK(s.tc.node_visits == 0);
  CHECK(s.tc.box_tests == 0);
  CHECK(s.tc.triangle_tests == 0);
}

TEST_CASE("the nearer child is searched first, whichever slot holds it", "[closest_hit]") {
  const Bvh bvh = build_bvh(two_floors(), {1});
  REQUIRE(bvh.nodes.size() == 1);  // one node fetch yields both leaves
  // From above, prim 0 is nearer; from below, prim 1. Either way the other
  // leaf's entry is past the hit, so it is never tested.
  const Search down = search(bvh, make_ray({0.25f, 0.25f, 1}, {0, 0, -1}));
  CHECK(down.hit.prim == 0);
  CHECK(down.hit.t == 1.0f);
  const Search up = search(bvh, make_ray({0.25f, 0.25f, -2}, {0, 0, 1}));
  CHECK(up.hit.prim == 1);
  CHECK(up.hit.t == 1.0f);
  for (const Search* s : {&down, &up}) {
    CHECK(s->tc.node_visits == 1);
    CHECK(s->tc.box_tests == 3);  // the root's box, then both children's
    CHECK(s->tc.triangle_tests == 1);
  }
}

TEST_CASE("a rejected candidate does not shorten the interval, any-hit stops at the first", "[closest_hit]") {
  const Bvh bvh = build_bvh(two_floors(), {1});
  Ray ray = make_ray({0.25f, 0.25f, 1}, {0, 0, -1});
  ray.parent_prim = 0;
  SelfIntersectionMethod primid;
  primid.primid = true;
  const Search s = search(bvh, ray, primid);
  CHECK(s.hit.prim == 1);  // prim 0 was met first and rejected: the far leaf is still searched
  CHECK(s.hit.t == 2.0f);
  CHECK(s.cc.rejected == 1);
  CHECK(s.tc.triangle_tests == 2);

  const Search any = search(bvh, make_ray({0.25f, 0.25f, -2}, {0, 0, 1}), {}, true);
  CHECK(any.hit.prim == 1);
  CHECK(any.tc.triangle_tests == 1);
  const Search any_rejected = search(bvh, ray, primid, true);
  CHECK(any_rejected.hit.prim == 1);  // the rejected candidate does not end an any-hit search
}

TEST_CASE("the traversal stack bound: depth - 1 entries must fit below 128", "[closest_hit]") {
  Bvh bvh = build_bvh(two_floors(), {1});
  CHECK_NOTHROW(check_traversal_depth(bvh));
  bvh.depth = kTraversalStackDepth;  // 127 entries at most
  CHECK_NOTHROW(check_traversal_depth(bvh));
  bvh.depth = kTraversalStackDepth + 1;
  CHECK_THROWS_AS(check_traversal_depth(bvh), std::runtime_error);
}
