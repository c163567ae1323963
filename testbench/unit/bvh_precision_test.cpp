// Nodes of two precisions (scene/bvh_precision.h): the cost model's choice
// computed by hand on a two-leaf tree, its limits (a low test that costs more
// is never chosen; a free one always is), and on the bunny boxes that hold
// what they held, in the narrow format, with the same hits and an oracle that
// accepts the tree.
#include <catch2/catch.hpp>

#include <cmath>

#include "datapath/closest_hit.h"
#include "datapath/reduced_precision.h"
#include "datapath/testers.h"
#include "exact/oracle.h"
#include "replay/replay_run.h"
#include "scene/bvh_precision.h"
#include "trace/trace_file.h"

using namespace vbsim;

namespace {

double area(const Bounds3f& b) {
  const double x = double(b.hi.x) - b.lo.x, y = double(b.hi.y) - b.lo.y, z = double(b.hi.z) - b.lo.z;
  return 2.0 * (x * y + y * z + z * x);
}

bool inside(const Bounds3f& in, const Bounds3f& out) {
  for (int a = 0; a < 3; ++a)
    if (in.lo[a] < out.lo[a] || in.hi[a] > out.hi[a]) return false;
  return true;
}

/// Two triangles far apart: a root node with two one-triangle leaves.
Scene two_leaves(float offset) {
  const Triangle a{{0, 0, 0}, {1, 0, 0}, {0, 1, offset}};
  const Triangle b{{8, 0, 0}, {9, 0, 0}, {8, 1, 0.5f}};
  return make_scene({a, b});
}

}  // namespace

TEST_CASE("the precision cost model chooses by hand on a root with two leaves", "[bvh][precision]") {
  // Leaf 0's box ends at z = 1 + 2^-10: 7 fraction bits round it up to
  // 1 + 2^-7. Leaf 1's box is exact in 7 bits (0.5): low costs only t_low.
  const float z = 1.0f + std::ldexp(1.0f, -10);
  const Scene scene = two_leaves(z);
  BvhBuildOptions options;
  options.max_leaf_size = 1;
  const Bvh plain = build_bvh(scene, options);
  REQUIRE(plain.nodes.size() == 1);
  const BvhNode& n = plain.nodes[0];
  const int c0 = n.child_bounds(0).lo.x == 0.0f ? 0 : 1;  // the child holding leaf 0
  const Bounds3f b0 = n.child_bounds(c0), b1 = n.child_bounds(1 - c0);
  const double root = area(plain.root_bounds);
  const double a0 = area(b0), a0_low = area(round_outward(b0, 7));
  REQUIRE(a0_low > a0);
  REQUIRE(area(round_outward(b1, 7)) == area(b1));
  // The root is full precision; leaf 0 goes low when
  //   t_low + a0_low / root <= t_high + a0 / root.
  const double gap = (a0_low - a0) / root;  // what rounding leaf 0's box costs
  for (const double t_low : {0.5 - 2 * gap, 0.5 - gap / 2}) {
    INFO("t_trav_low " << t_low);
    options.low_precision = {true, 7, 0.5, t_low};
    const Bvh marked = build_bvh(scene, options);
    const bool leaf0_low = t_low + a0_low / root <= 0.5 + a0 / root;
    CHECK(leaf0_low == (t_low < 0.5 - gap));
    const Bounds3f m0 = marked.nodes[0].child_bounds(c0);
    if (leaf0_low) {
      CHECK(area(m0) == a0_low);  // stored rounded
      CHECK(marked.low_precision_node[0] == 1);  // both children low: the low pool's
    } else {
      CHECK(area(m0) == a0);
      CHECK(marked.low_precision_node[0] == 0);
    }
    CHECK(area(marked.nodes[0].child_bounds(1 - c0)) == area(b1));  // exact either way
  }
}

TEST_CASE("nodes of two precisions on the bunny: the narrow format, boxes that hold what they held, the same hits",
          "[bvh][precision]") {
  const SceneAndBvh sb = load_trace_scene(open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl")->header());
  BvhBuildOptions options;
  options.low_precision = {true, 7, 0.5, 0.47};  // rtcore-systemc's defaults
  const Bvh marked = build_bvh(sb.scene, options);
  const Bvh& plain = sb.bvh;
  REQUIRE(marked.nodes.size() == plain.nodes.size());
  REQUIRE(marked.low_precision_node.size() == marked.nodes.size());
  size_t low_children = 0, low_nodes = 0;
  for (size_t i = 0; i < marked.nodes.size(); ++i) {
    low_nodes += marked.low_precision_node[i];
    int low_here = 0;
    for (int c = 0; c < 2; ++c) {
      const Bounds3f m = marked.nodes[i].child_bounds(c), p = plain.nodes[i].child_bounds(c);
      CHECK(marked.nodes[i].ref[c] == plain.nodes[i].ref[c]);
      CHECK(marked.nodes[i].count[c] == plain.nodes[i].count[c]);
      CHECK(inside(p, m));  // holds what it held
      if (!(m.lo == p.lo && m.hi == p.hi)) {
        CHECK(round_outward(m, 7).lo == m.lo);  // in the narrow format
        CHECK(round_outward(m, 7).hi == m.hi);
        ++low_here;
      }
    }
    if (low_here == 2) CHECK(marked.low_precision_node[i] == 1);
    low_children += low_here;
  }
  CHECK(low_children > marked.nodes.size() / 2);  // the model finds most narrow boxes worth it here
  CHECK(low_nodes > 0);
  CHECK(low_nodes < marked.nodes.size());
  CHECK_NOTHROW(Oracle(sb.scene, marked));  // every triangle inside every box above it

  // The same closest hits on the bundled trace's rays, with at least as many box tests.
  auto src = open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl");
  TraceRay tr;
  size_t rays = 0, differ = 0;
  TraversalCounters tc_plain, tc_marked;
  CandidateCounters cc;
  const CandidateFilter filter(SelfIntersectionMethod{});
  while (src->next(tr)) {
    Ray r;
    r.o = tr.o;
    r.d = tr.d;
    r.tmin = tr.tmin;
    r.tmax = tr.tmax;
    const Hit a = closest_hit<ThreeHalfPlaneTester>(plain, r, filter, cc, tc_plain);
    const Hit b = closest_hit<ThreeHalfPlaneTester>(marked, r, filter, cc, tc_marked);
    differ += a.prim != b.prim || a.t != b.t;
    ++rays;
  }
  CHECK(rays == 1008);
  CHECK(differ == 0);
  CHECK(tc_marked.box_tests >= tc_plain.box_tests);
  CHECK(tc_marked.node_visits >= tc_plain.node_visits);
}

TEST_CASE("a low-precision test that costs more is never chosen, a free one always", "[bvh][precision]") {
  const SceneAndBvh sb = load_trace_scene(open_trace(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl")->header());
  BvhBuildOptions options;
  options.low_precision = {true, 7, 0.5, 0.6};  // a narrow box is never smaller: never cheaper
  const Bvh none = build_bvh(sb.scene, options);
  size_t marked = 0;
  for (const uint8_t m : none.low_precision_node) marked += m;
  CHECK(marked == 0);
  for (size_t i = 0; i < none.nodes.size(); ++i)
    for (int c = 0; c < 2; ++c) CHECK(none.nodes[i].child_bounds(c).lo == sb.bvh.nodes[i].child_bounds(c).lo);
  options.low_precision = {true, 7, 1000.0, 0.0};  // low always cheaper
  const Bvh all = build_bvh(sb.scene, options);
  for (const uint8_t m : all.low_precision_node) CHECK(m == 1);
  CHECK_THROWS_WITH(build_bvh(sb.scene, BvhBuildOptions{4, BvhQuality::High, BvhBuilder::Embree, 1.0f,
                                                        {true, 23, 0.5, 0.47}}),
                    Catch::Contains("bvh.low_precision.mantissa_bits"));
}
