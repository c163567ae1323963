// The built-in unit modules answer through their interfaces what the datapath
// computes (what the scheduler computes inline for them), with the schedule of
// their reservation table.
#include <catch2/catch.hpp>

#include "datapath/avoidance_unit.h"
#include "datapath/ray_box_tester.h"
#include "datapath/testers.h"
#include "hw/core/pipeline_units.h"
#include "hw/simulation_context.h"
#include "three_floors.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

Ray slanted() {
  Ray r;
  r.o = {0.25f, 0.3f, 1.0f};
  r.d = {0.01f, -0.02f, -1.0f};
  r.kind = RayKind::Reflect;
  r.sign = 1;
  return r;
}

}  // namespace

TEST_CASE("the built-in box unit answers the slab test of both children, and the root's", "[unit][units]") {
  const SimulationContext context;
  const ThreeFloors f;
  BoxUnit unit("box", UnitConfig{1, 4, 1});
  const Ray ray = slanted();
  const RayBoxTester latched(ray);
  BoxOp op;
  op.ray = &ray;
  op.tmax = ray.tmax;
  op.node = 0;
  op.node_record = &f.bvh.nodes[0];
  op.ready = 3;
  const BoxAnswer a = unit.test_boxes(op);
  float e0, e1;
  CHECK(a.met == latched.hits(f.bvh.nodes[0], ray.tmax, e0, e1));
  CHECK(a.met == 3u);  // both children: node 1 (entry 1) and prim 2's leaf (entry 3)
  CHECK(a.entry[0] == e0);
  CHECK(a.entry[1] == e1);
  CHECK(a.schedule.issue == 3);
  CHECK(a.schedule.done == 7);
  op.node = BoxOp::kRootBox;
  op.node_record = nullptr;
  op.root = &f.bvh.root_bounds;
  op.latched = &latched;
  const BoxAnswer root = unit.test_boxes(op);
  CHECK(root.met == 1u);
  CHECK(root.schedule.issue == 4);  // one pipeline, issue interval 1: the next cycle
}

TEST_CASE("the built-in triangle tester answers its tester kind's hit and front/back bit", "[unit][units]") {
  const SimulationContext context;
  const ThreeFloors f;
  const Ray ray = slanted();
  for (TesterKind kind : {TesterKind::ThreeHalfPlane, TesterKind::MollerTrumbore, TesterKind::PbrtWatertight}) {
    INFO(tester_name(kind));
    TriangleTester unit(tester_name(kind), UnitConfig{2, 9, 1}, kind);
    TriangleOp op;
    op.ray = &ray;
    op.triangle = &f.scene.triangles[0];
    op.tmax = ray.tmax;
    op.ready = 10;
    const TriangleAnswer a = unit.test_triangle(op);
    Hit want;
    bool hit = false;
    if (kind == TesterKind::ThreeHalfPlane) hit = ThreeHalfPlaneTester(ray).intersect(*op.triangle, op.tmax, want);
    if (kind == TesterKind::MollerTrumbore) hit = MollerTrumboreTester(ray).intersect(*op.triangle, op.tmax, want);
    if (kind == TesterKind::PbrtWatertight) hit = PbrtWatertightTester(ray).intersect(*op.triangle, op.tmax, want);
    REQUIRE(hit);
    CHECK(a.candidate);
    CHECK(a.hit.t == want.t);
    CHECK(a.hit.u == want.u);
    CHECK(a.hit.v == want.v);
    CHECK(a.hit.front == 1);  // going down onto a floor whose normal is +z
    CHECK(a.schedule.done == a.schedule.issue + 9);
    op.tmax = 0.5f;  // the floor at t = 1 lies beyond the interval
    CHECK_FALSE(unit.test_triangle(op).candidate);
  }
}

TEST_CASE("the built-in avoidance unit answers avoidance_decide", "[unit][units]") {
  const SimulationContext context;
  const ThreeFloors f;
  AvoidanceConfig cfg;
  AvoidanceUnit unit("avoidance", UnitConfig{1, 6, 1}, cfg, true);
  Ray ray = slanted();
  ray.o.z = 1e-7f;  // just above the floor: a suspect too close to be real
  Hit h;
  REQUIRE(ThreeHalfPlaneTester(ray).intersect(f.scene.triangles[0], ray.tmax, h));
  AvoidanceOp op;
  op.ray = &ray;
  op.triangle = &f.scene.triangles[0];
  op.candidate = &h;
  op.sign_bit = ray.sign;
  op.front = h.front;
  op.config = &cfg;
  const AvoidanceAnswer a = unit.decide(op);
  const AvoidanceDecision want = avoidance_decide(cfg, ray, f.scene.triangles[0], h);
  CHECK(want.reject);
  CHECK(a.decision.reject == want.reject);
  CHECK(a.decision.invalid == want.invalid);
  CHECK(a.schedule.done == a.schedule.issue + 6);
}
