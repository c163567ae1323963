// PortUnits: the BvhStepper units policy (datapath/bvh_stepper.h) of a core
// whose units are reached through their interfaces (hw/unit_interfaces.h),
// used by the scheduler when any unit or memory of the accelerator is
// replaced. Each answer the stepper asks for becomes one operation of the
// core's unit, carrying the payload (hw/core/unit_operations.h); the unit's
// schedule is left in the UnitCall the scheduler filled for the step.
//
// A built-in module bound to the port is called without the virtual call: its
// reservation table for the schedule and the slot's latched datapath state
// (RayBoxTester, the Tester) for the answer, as its interface call computes it.
// A replacement's answers are checked (issue >= ready, done >= issue; a
// triangle candidate inside the interval) and its operations counted in
// CoreCounters::replaced_units.
//
// The avoidance unit is asked for a suspect candidate only (the ray's parent
// sign bit equal to the front/back bit) and only when the method's policy
// tests (`avoidance_in_use`); under policy sign-only the bit alone rejects,
// with no operation, as in the built-in timing.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <systemc>

#include "datapath/avoidance_unit.h"
#include "datapath/ray_box_tester.h"
#include "hw/core/pipeline_units.h"
#include "hw/core/ray_test_core.h"
#include "hw/core/unit_operations.h"
#include "hw/hw_counters.h"
#include "hw/scheduler/cycle_engine.h"
#include "scene/bvh.h"

namespace vbsim::hw {

/// What the scheduler tells the units of one step, and what they leave it.
struct UnitCall {
  const CoreBinding* core = nullptr;
  OpSource from;
  uint64_t ready = 0, now = 0;  ///< the operands' cycle (box, triangle) and the event's
  UnitSchedule box{0, 0}, triangle{0, 0}, avoidance{0, 0};
  bool box_called = false, avoidance_called = false;
  bool low_pool = false;  ///< the node step's boxes go to the low-precision pool (CoreBinding::box_low)
};

/// The name of the instance implementing `iface`, or `fallback`.
inline std::string unit_instance_name(sc_core::sc_interface* iface, const std::string& fallback) {
  const auto* o = dynamic_cast<const sc_core::sc_object*>(iface);
  return o ? std::string(o->name()) : fallback;
}

/// A replacement's schedule, checked and counted as unit `unit` of `c`.
inline UnitSchedule checked_schedule(const CoreBinding& c, int unit, sc_core::sc_interface* u, const char* call,
                                     const UnitSchedule& s, uint64_t ready) {
  if (s.issue < ready || s.done < s.issue)
    throw std::runtime_error(fmt::format(
        "{}: an operation ready at cycle {} was scheduled to issue at {} and be done at {}: {} must answer "
        "issue >= ready and done >= issue",
        unit_instance_name(u, std::string(c.core->name()) + ".unit"), ready, s.issue, s.done, call));
  UnitCounters& counted = c.core->counters.replaced_units[unit];
  ++counted.ops;
  counted.wait_cycles += s.issue - ready;
  return s;
}

template <class Tester>
class PortUnits {
 public:
  PortUnits(UnitCall& call, bool avoidance_in_use) : call_(call), avoidance_in_use_(avoidance_in_use) {}

  bool root_box(const Ray& ray, const RayBoxTester& latched, const Bounds3f& b, float tmax) {
    BoxOp op = box_op(ray, latched, tmax);
    op.root = &b;
    return (box(op).met & 1u) != 0u;
  }

  unsigned node_boxes(const Ray& ray, const RayBoxTester& latched, uint32_t node, const BvhNode& n, float tmax,
                      float& entry0, float& entry1) {
    BoxOp op = box_op(ray, latched, tmax);
    op.node = node;
    op.node_record = &n;
    const BoxAnswer a = box(op);
    entry0 = a.entry[0];
    entry1 = a.entry[1];
    return a.met & 3u;
  }

  unsigned narrow_node_boxes(const Ray& ray, const RayBoxTester& latched, const NarrowBoxTester& narrow,
                             uint32_t node, const BvhNode& n, float tmax, float& entry0, float& entry1) {
    BoxOp op = box_op(ray, latched, tmax);
    op.node = node;
    op.node_record = &n;
    op.narrow = &narrow;
    const BoxAnswer a = box(op);
    entry0 = a.entry[0];
    entry1 = a.entry[1];
    return a.met & 3u;
  }

  template <int W>
  unsigned wide_node_boxes(const Ray& ray, const RayBoxTester& latched, uint32_t node, const WideBvhNode<W>& n,
                           float tmax, float* entry) {
    BoxOp op = box_op(ray, latched, tmax);
    op.node = node;
    if constexpr (W == 4) op.node4_record = &n;
    else op.node8_record = &n;
    const BoxAnswer a = box(op);
    for (int c = 0; c < W; ++c) entry[c] = a.entry[c];
    return a.met & ((1u << n.children) - 1u);
  }

  bool triangle(const Ray& ray, const Tester& latched, uint32_t index, const BvhTriangle& bt, float tmax, Hit& h) {
    const CoreBinding& c = *call_.core;
    if (c.triangle_builtin) {
      call_.triangle = c.triangle_builtin->schedule_inline(call_.ready, call_.now);
      return latched.intersect(bt.tri, tmax, h);
    }
    TriangleOp op;
    op.from = call_.from;
    op.index = index;
    op.prim = static_cast<int32_t>(bt.prim);
    op.triangle = &bt.tri;
    op.ray = &ray;
    op.tmax = tmax;
    op.ready = call_.ready;
    op.now = call_.now;
    const TriangleAnswer a = c.triangle->test_triangle(op);
    call_.triangle = checked_schedule(c, CoreCounters::kTriangle, c.triangle, "TriangleTesterIf::test_triangle",
                                      a.schedule, op.ready);
    if (!a.candidate) return false;
    if (!(a.hit.t > ray.tmin && a.hit.t < tmax))
      throw std::runtime_error(fmt::format(
          "{}: triangle {} answered a candidate at t = {}, outside the ray's interval ({}, {}): "
          "TriangleTesterIf::test_triangle reports candidates inside it only",
          unit_instance_name(c.triangle, std::string(c.core->name()) + ".triangle_tester"), index, a.hit.t, ray.tmin,
          tmax));
    h.t = a.hit.t;
    h.u = a.hit.u;
    h.v = a.hit.v;
    h.front = a.hit.front;
    return true;
  }

  AvoidanceDecision avoidance(const AvoidanceConfig& cfg, const Ray& ray, uint32_t index, const Triangle& tri,
                              const Hit& h) {
    if (!avoidance_in_use_ || ray.sign != h.front) return avoidance_decide(cfg, ray, tri, h);  // no operation
    const CoreBinding& c = *call_.core;
    const uint64_t ready = call_.triangle.done;  // the tester's front/back bit
    call_.avoidance_called = true;
    if (c.avoidance_builtin) {
      call_.avoidance = c.avoidance_builtin->schedule_inline(ready, call_.now);
      return avoidance_decide(cfg, ray, tri, h);
    }
    AvoidanceOp op;
    op.from = call_.from;
    op.index = index;
    op.candidate = &h;
    op.triangle = &tri;
    op.ray = &ray;
    op.sign_bit = ray.sign;
    op.front = h.front;
    op.config = &cfg;
    op.ready = ready;
    op.now = call_.now;
    AvoidanceAnswer a = c.avoidance->decide(op);
    call_.avoidance =
        checked_schedule(c, CoreCounters::kAvoidance, c.avoidance, "AvoidanceUnitIf::decide", a.schedule, ready);
    a.decision.suspect = true;
    return a.decision;
  }

 private:
  BoxOp box_op(const Ray& ray, const RayBoxTester& latched, float tmax) const {
    BoxOp op;
    op.from = call_.from;
    op.ray = &ray;
    op.latched = &latched;
    op.tmax = tmax;
    op.ready = call_.ready;
    op.now = call_.now;
    return op;
  }

  BoxAnswer box(const BoxOp& op) {
    const CoreBinding& c = *call_.core;
    call_.box_called = true;
    // The low-precision pool is always built-in; the box unit may be a replacement.
    if (BoxUnit* builtin = call_.low_pool ? c.box_low : c.box_builtin) {
      BoxAnswer a = BoxUnit::compute(op);
      a.schedule = builtin->schedule_inline(op.ready, op.now);
      call_.box = a.schedule;
      return a;
    }
    const BoxAnswer a = c.box->test_boxes(op);
    call_.box = checked_schedule(c, CoreCounters::kBox, c.box, "BoxUnitIf::test_boxes", a.schedule, op.ready);
    return a;
  }

  UnitCall& call_;
  bool avoidance_in_use_;
};

}  // namespace vbsim::hw
