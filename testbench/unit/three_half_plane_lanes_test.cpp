// The three-half-plane tester's four-lane form (datapath/three_half_plane_lanes.h)
// and the leaf step that uses it (search_rules.h, search_leaf_lanes): lane for
// lane the same bits as intersect() on hand-made hard cases (exact zeros of the
// edge functions, rays in a triangle's plane, degenerate and huge triangles,
// distances at the bounds) and random ones; and every search, at every node
// width and leaf size, with and without a filter that rejects, returns the
// same hit and the same counts with the lanes as without them.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bench/functional_bench.h"
#include "datapath/closest_hit.h"
#include "datapath/self_intersection_method.h"
#include "datapath/testers.h"
#include "datapath/three_half_plane_lanes.h"
#include "scene/bvh.h"
#include "scene/triangle_lanes.h"
#include "bvh_checks.h"

using namespace vbsim;

namespace {

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_hit(const Hit& a, const Hit& b) {
  return a.prim == b.prim && same_bits(a.t, b.t) && same_bits(a.u, b.u) && same_bits(a.v, b.v) &&
         a.front == b.front;
}

BvhTriangle bt(const Triangle& t, uint32_t prim) { return BvhTriangle{t, prim}; }

}  // namespace

#if defined(__SSE2__)  // the four-lane form exists on SSE2 hosts (testers.h)
namespace {

/// What the lane test found over many groups.
struct LaneTally {
  int met = 0, redo = 0, missed = 0, rechecked = 0;
};

/// Tests `tris` (any count) four at a time against `ray` with upper bound
/// `bound`, and requires of every lane what intersect() answers: a lane not
/// flagged for the redo is met, and then below(bound), exactly when intersect()
/// hits, with the same bits, and held to a smaller bound it answers as
/// intersect() with that bound.
void require_lanes_match(const Ray& ray, const std::vector<BvhTriangle>& tris, float bound, LaneTally& tally) {
  TriangleLanes lanes;
  lanes.fill(tris.data(), tris.size());
  const ThreeHalfPlaneTester tester(ray);
  for (uint32_t g = 0; g < tris.size(); g += 4) {
    const int n = static_cast<int>(std::min<size_t>(4, tris.size() - g));
    ThreeHalfPlaneTester::LaneHits lh;
    tester.intersect_lanes(lanes, g, n, bound, lh);
    REQUIRE((lh.met & lh.redo) == 0u);
    REQUIRE((lh.met | lh.redo) >> n == 0u);  // no lane past the group
    for (int l = 0; l < n; ++l) {
      const Triangle& tri = tris[g + static_cast<uint32_t>(l)].tri;
      Hit expect;
      const bool hit = tester.intersect(tri, bound, expect);
      if ((lh.redo >> l) & 1u) {
        ++tally.redo;
        continue;
      }
      INFO("triangle " << g + static_cast<uint32_t>(l));
      const bool met = ((lh.met >> l) & 1u) != 0u;
      if (hit) REQUIRE(met);  // met: every check before the division passed
      REQUIRE((met && lh.below(l, bound)) == hit);
      if (!hit) {
        ++tally.missed;
        continue;
      }
      ++tally.met;
      REQUIRE(same_hit(lh.hit(l), expect));
      for (float smaller : {expect.t, std::nextafter(expect.t, 0.0f), 0.5f * (expect.t + bound)}) {
        if (!(smaller <= bound)) continue;
        Hit again;
        REQUIRE(lh.below(l, smaller) == tester.intersect(tri, smaller, again));
        ++tally.rechecked;
      }
    }
  }
}

}  // namespace

TEST_CASE("the four-lane three-half-plane test answers as intersect() on hand-made hard cases",
          "[tester][lanes]") {
  LaneTally tally;
  const Triangle right{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // Ng = +z
  // Straight down through (0.25, 0.5): t = 2 exactly (hand: o.z = 2, d.z = -1).
  Ray down;
  down.o = {0.25f, 0.5f, 2};
  down.d = {0, 0, -1};
  {
    std::vector<BvhTriangle> tris = {
        bt(right, 0),
        bt({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, 1),          // the same, one unit higher: t = 1
        bt({{5, 5, 0}, {6, 5, 0}, {5, 6, 0}}, 2),          // off to the side: a miss
        bt({{0, 0, 0}, {1, 1, 0}, {2, 2, 0}}, 3),          // no area: det 0
        bt({{0, 0, -1}, {1, 0, -1}, {0, 1, -1}}, 4),       // t = 3
        bt({{0.25f, 0, 0}, {0.25f, 1, 0}, {0.25f, 0, 2}}, 5),  // the ray lies in its plane x = 0.25
    };
    require_lanes_match(down, tris, std::numeric_limits<float>::infinity(), tally);
    const int met_all = tally.met;
    CHECK(met_all == 3);  // triangles 0, 1, 4
    // Bounds at the hits: t < bound is open, so a bound of exactly 2 drops the hit at 2.
    require_lanes_match(down, tris, 2.0f, tally);
    CHECK(tally.met == met_all + 1);  // only t = 1 stays below 2
    require_lanes_match(down, tris, std::nextafter(2.0f, 3.0f), tally);
    Ray late = down;
    late.tmin = 1.0f;  // t > tmin is open too: the hit at 1 goes
    require_lanes_match(late, tris, 10.0f, tally);
  }
  {
    // A ray along z exactly through a shared vertex and a shared edge: the
    // sheared vertices sit exactly on the axis, so edge functions are exactly
    // 0 and intersect() redoes them in double; the lanes only flag those.
    Ray at_vertex;
    at_vertex.o = {0, 0, 5};
    at_vertex.d = {0, 0, -1};
    Ray at_edge;
    at_edge.o = {0.5f, 0, 5};
    at_edge.d = {0, 0, -1};
    const std::vector<BvhTriangle> fan = {
        bt(right, 0), bt({{0, 0, 0}, {0, 1, 0}, {-1, 0, 0}}, 1), bt({{0, 0, 0}, {-1, 0, 0}, {0, -1, 0}}, 2),
        bt({{0, 0, 0}, {0, -1, 0}, {1, 0, 0}}, 3), bt({{3, 3, 0}, {4, 3, 0}, {3, 4, 0}}, 4)};
    const int redo_before = tally.redo;
    require_lanes_match(at_vertex, fan, std::numeric_limits<float>::infinity(), tally);
    require_lanes_match(at_edge, fan, std::numeric_limits<float>::infinity(), tally);
    CHECK(tally.redo - redo_before >= 6);  // 4 at the vertex, 2 at the edge
  }
  {
    // Coordinates near float's limit: products overflow to infinity and
    // differences of infinities give NaN; the lanes must still agree.
    const float big = 3e38f;
    Ray far;
    far.o = {-big, 0.5f, 0.25f};
    far.d = {1, 1e-30f, 2e-30f};
    const std::vector<BvhTriangle> huge = {bt({{big, -big, -big}, {big, big, -big}, {big, 0, big}}, 0),
                                           bt({{0, -1, -1}, {0, 1, -1}, {0, 0, 1}}, 1),
                                           bt({{-big, -big, 0}, {big, -big, 0}, {0, big, 0}}, 2)};
    require_lanes_match(far, huge, std::numeric_limits<float>::infinity(), tally);
  }
  CHECK(tally.met >= 6);
  CHECK(tally.missed >= 10);
  CHECK(tally.rechecked >= 10);
}

TEST_CASE("the four-lane three-half-plane test answers as intersect() on random triangles and rays",
          "[tester][lanes]") {
  std::mt19937 rng(20261203);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  LaneTally tally;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<BvhTriangle> tris;
    const int count = 1 + trial % 9;  // groups of 1 to 4 lanes
    for (int i = 0; i < count; ++i) {
      const Vec3f c{unit(rng), unit(rng), unit(rng)};
      const float size = (i % 3 == 0) ? 1.0f : 0.2f;
      const auto corner = [&] { return c + size * Vec3f{unit(rng), unit(rng), unit(rng)}; };
      tris.push_back(bt({corner(), corner(), corner()}, static_cast<uint32_t>(i)));
    }
    // Every other trial shares a vertex between triangles (as a mesh does) and
    // aims the ray exactly at it.
    Ray ray;
    ray.o = 4.0f * Vec3f{unit(rng), unit(rng), unit(rng)};
    if (trial % 2 == 0 && count >= 2) {
      tris[1].tri.v0 = tris[0].tri.v0;
      ray.d = tris[0].tri.v0 - ray.o;
    } else {
      const Triangle& aim = tris[static_cast<size_t>(trial) % tris.size()].tri;
      ray.d = (0.3f * aim.v0 + 0.3f * aim.v1 + 0.4f * aim.v2) - ray.o;
    }
    if (trial % 5 == 0) ray.tmin = 0.3f;
    const float bound = trial % 3 == 0 ? std::numeric_limits<float>::infinity() : 0.5f + 0.5f * (unit(rng) + 1.0f);
    require_lanes_match(ray, tris, bound, tally);
    // Bounds exactly at each hit's distance, where the scaled check and the
    // rounded distance can disagree: both must be made as intersect() makes them.
    const ThreeHalfPlaneTester tester(ray);
    for (const BvhTriangle& t : tris) {
      Hit h;
      if (!tester.intersect(t.tri, bound, h)) continue;
      for (float at : {h.t, std::nextafter(h.t, INFINITY)}) require_lanes_match(ray, tris, at, tally);
    }
  }
  CHECK(tally.met > 1000);
  CHECK(tally.missed > 1000);
  CHECK(tally.rechecked > 1000);
}

#endif  // __SSE2__

TEST_CASE("searches give the same hits and counts with triangle lanes as without", "[tester][lanes][bvh]") {
  const Scene bunny = load_scene(test::kBunnyPath);
  const std::vector<TraceRay> rays = bench_rays(bunny, 1500, 11);
  SelfIntersectionMethod validity;
  std::string error;
  REQUIRE(parse_method("validity-bit", validity, error));
  const CandidateFilter none(SelfIntersectionMethod{}), rejecting(validity);
  struct Tree {
    int width, leaf;
    BvhBuilder builder;
  };
  for (const Tree& t : {Tree{2, 4, BvhBuilder::Embree}, Tree{4, 4, BvhBuilder::Embree}, Tree{8, 4, BvhBuilder::Embree},
                        Tree{4, 16, BvhBuilder::SweepSah}, Tree{2, 7, BvhBuilder::SweepSah}}) {
    BvhBuildOptions o;
    o.width = t.width;
    o.max_leaf_size = t.leaf;
    o.builder = t.builder;
    o.traversal_cost = t.leaf > 4 ? 4.0f : 1.0f;  // larger leaves: groups of more than four
    const Bvh with = build_bvh(bunny, o);
    Bvh without = with;
    without.lanes = TriangleLanes{};
    REQUIRE(with.triangle_lanes() != nullptr);
#if defined(__SSE2__)
    STATIC_REQUIRE(HasLaneForm<ThreeHalfPlaneTester>::value);  // so `with` is searched four lanes at a time
#endif
    REQUIRE(without.triangle_lanes() == nullptr);
    INFO("width " << t.width << ", leaves up to " << t.leaf);
    uint64_t hits = 0, children = 0, rejected = 0;
    for (const TraceRay& tr : rays) {
      Ray primary;
      primary.o = tr.o;
      primary.d = tr.d;
      CandidateCounters cc0;
      TraversalCounters tc0;
      const Hit first = closest_hit<ThreeHalfPlaneTester>(without, primary, none, cc0, tc0);
      std::vector<Ray> probes = {primary};
      if (first.prim >= 0) {
        // A child from the hit point, into the surface and back out of it:
        // the parent is among the candidates, and validity-bit rejects it.
        const Triangle& tri = bunny.triangles[static_cast<size_t>(first.prim)];
        Ray child;
        child.o = (1.0f - first.u - first.v) * tri.v0 + first.u * tri.v1 + first.v * tri.v2;
        child.kind = RayKind::Reflect;
        child.parent_prim = first.prim;
        const Vec3f ng = geometric_normal(tri);
        for (float s : {1.0f, -1.0f}) {
          child.d = s * ng + 0.3f * primary.d;
          child.sign = dot(child.d, ng) < 0.0f ? 1 : 0;
          probes.push_back(child);
          ++children;
        }
      }
      for (const Ray& ray : probes)
        for (const CandidateFilter* filter : {&none, &rejecting})
          for (bool any : {false, true}) {
            CandidateCounters cc[2];
            TraversalCounters tc[2];
            const Hit a = closest_hit<ThreeHalfPlaneTester>(with, ray, *filter, cc[0], tc[0], any);
            const Hit b = closest_hit<ThreeHalfPlaneTester>(without, ray, *filter, cc[1], tc[1], any);
            REQUIRE(same_hit(a, b));
            REQUIRE(tc[0].node_visits == tc[1].node_visits);
            REQUIRE(tc[0].box_tests == tc[1].box_tests);
            REQUIRE(tc[0].triangle_tests == tc[1].triangle_tests);
            REQUIRE(tc[0].stack_pushes == tc[1].stack_pushes);
            REQUIRE(tc[0].stack_pops == tc[1].stack_pops);
            REQUIRE(cc[0].candidates == cc[1].candidates);
            REQUIRE(cc[0].rejected == cc[1].rejected);
            REQUIRE(cc[0].suspects == cc[1].suspects);
            hits += a.prim >= 0;
            rejected += cc[0].rejected;
          }
    }
    CHECK(hits > 1000);
    CHECK(children > 500);
    CHECK(rejected > 100);  // the filter's path was taken
  }
}
