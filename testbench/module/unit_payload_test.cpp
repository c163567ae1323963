// What replacement units see: the operations' payloads (node and triangle
// indices in traversal order per ray, the records they point at, the ray, the
// interval, the slot), checked by hand on three floors and against the
// datapath's own traversal on the bundled trace; and when, in SystemC time,
// a unit is called relative to the cycle its operation carries.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "../unit/three_floors.h"
#include "accelerator_harness.h"
#include "datapath/bvh_stepper.h"
#include "hw/core/pipeline_units.h"
#include "hw/cycle_clock.h"
#include "hw/cycle_replay.h"
#include "replay/replay_run.h"
#include "trace/trace_source.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

/// One operation as a unit saw it.
struct Seen {
  char unit;       ///< 'b' box, 't' triangle, 'a' avoidance
  uint32_t index;  ///< node (BoxOp::kRootBox for the root), triangle
  float tmax;
  uint32_t slot, core;
  int64_t ray_id;
  bool operator==(const Seen& o) const { return unit == o.unit && index == o.index; }
};

/// What the recording units saw, by trace position; and the SystemC time of each call.
struct Record {
  const Bvh* bvh = nullptr;
  std::map<uint64_t, std::vector<Seen>> by_ray;
  uint64_t calls = 0, payload_errors = 0;
  double period_ps = 0;
  int64_t min_ahead = 1 << 30, max_ahead = -(1 << 30);  ///< now - (SystemC time in cycles)
  void seen(const OpSource& from, char unit, uint32_t index, float tmax, uint64_t now) {
    by_ray[from.trace_index].push_back({unit, index, tmax, from.slot, from.core, from.ray_id});
    ++calls;
    const double cycles = sc_core::sc_time_stamp().to_seconds() * 1e12 / period_ps;
    const int64_t c = static_cast<int64_t>(std::llround(cycles));
    min_ahead = std::min(min_ahead, static_cast<int64_t>(now) - c);
    max_ahead = std::max(max_ahead, static_cast<int64_t>(now) - c);
  }
};

/// The built-in answers one cycle after the operands, recorded.
class RecordingBoxUnit final : public sc_core::sc_module, public BoxUnitIf {
 public:
  RecordingBoxUnit(sc_core::sc_module_name n, Record& r) : sc_core::sc_module(n), r_(r) {}
  BoxAnswer test_boxes(const BoxOp& op) override {
    r_.seen(op.from, 'b', op.node, op.tmax, op.now);
    const Bvh& b = *r_.bvh;
    const bool records_right =
        op.node == BoxOp::kRootBox
            ? op.root == &b.root_bounds && !op.node_record && !op.node4_record && !op.node8_record
            : !op.root && op.node_record == (b.width == 2 ? &b.nodes[op.node] : nullptr) &&
                  op.node4_record == (b.width == 4 ? &b.nodes4[op.node] : nullptr) &&
                  op.node8_record == (b.width == 8 ? &b.nodes8[op.node] : nullptr);
    if (!records_right) ++r_.payload_errors;
    if (!op.ray || !op.latched || op.ready < op.now) ++r_.payload_errors;
    BoxAnswer a = BoxUnit::compute(op);
    a.schedule = {op.ready, op.ready + 1};
    return a;
  }

 private:
  Record& r_;
};

class RecordingTriangleTester final : public sc_core::sc_module, public TriangleTesterIf {
 public:
  RecordingTriangleTester(sc_core::sc_module_name n, Record& r) : sc_core::sc_module(n), r_(r) {}
  TriangleAnswer test_triangle(const TriangleOp& op) override {
    r_.seen(op.from, 't', op.index, op.tmax, op.now);
    const BvhTriangle& bt = r_.bvh->tris[op.index];
    if (op.triangle != &bt.tri || op.prim != static_cast<int32_t>(bt.prim) || !op.ray) ++r_.payload_errors;
    TriangleAnswer a = TriangleTester::compute(TesterKind::ThreeHalfPlane, op);
    a.schedule = {op.ready, op.ready + 1};
    return a;
  }

 private:
  Record& r_;
};

class RecordingAvoidanceUnit final : public sc_core::sc_module, public AvoidanceUnitIf {
 public:
  RecordingAvoidanceUnit(sc_core::sc_module_name n, Record& r) : sc_core::sc_module(n), r_(r) {}
  AvoidanceAnswer decide(const AvoidanceOp& op) override {
    r_.seen(op.from, 'a', op.index, 0, op.now);
    // Asked for suspects only: the parent sign bit equal to the front/back bit.
    if (op.sign_bit != op.front || op.sign_bit != op.ray->sign || op.front != op.candidate->front ||
        op.triangle != &r_.bvh->tris[op.index].tri || !op.config)
      ++r_.payload_errors;
    AvoidanceAnswer a;
    a.decision = avoidance_decide(*op.config, *op.ray, *op.triangle, *op.candidate);
    a.schedule = {op.ready, op.ready + 1};
    return a;
  }

 private:
  Record& r_;
};

AcceleratorUnits recording_units(Record& r) {
  AcceleratorUnits u;
  u.box_unit = [&r](const char* n, uint32_t, const HwConfig&) { return std::make_unique<RecordingBoxUnit>(n, r); };
  u.triangle_tester = [&r](const char* n, uint32_t, const HwConfig&) {
    return std::make_unique<RecordingTriangleTester>(n, r);
  };
  u.avoidance_unit = [&r](const char* n, uint32_t, const HwConfig&) {
    return std::make_unique<RecordingAvoidanceUnit>(n, r);
  };
  return u;
}

/// The datapath's answers (BuiltinUnits), recorded in the order the stepper asks.
struct ReferenceUnits {
  std::vector<Seen>& out;
  bool avoidance_in_use;
  bool root_box(const Ray& ray, const RayBoxTester& l, const Bounds3f& b, float tmax) {
    out.push_back({'b', BoxOp::kRootBox, tmax, 0, 0, 0});
    return BuiltinUnits::root_box(ray, l, b, tmax);
  }
  unsigned node_boxes(const Ray& ray, const RayBoxTester& l, uint32_t node, const BvhNode& n, float tmax, float& e0,
                      float& e1) {
    out.push_back({'b', node, tmax, 0, 0, 0});
    return BuiltinUnits::node_boxes(ray, l, node, n, tmax, e0, e1);
  }
  unsigned narrow_node_boxes(const Ray& ray, const RayBoxTester& l, const NarrowBoxTester& nb, uint32_t node,
                             const BvhNode& n, float tmax, float& e0, float& e1) {
    out.push_back({'b', node, tmax, 0, 0, 0});
    return BuiltinUnits::narrow_node_boxes(ray, l, nb, node, n, tmax, e0, e1);
  }
  template <int W>
  unsigned wide_node_boxes(const Ray& ray, const RayBoxTester& l, uint32_t node, const WideBvhNode<W>& n, float tmax,
                           float* entry) {
    out.push_back({'b', node, tmax, 0, 0, 0});
    return BuiltinUnits::wide_node_boxes(ray, l, node, n, tmax, entry);
  }
  template <class Tester>
  bool triangle(const Ray& ray, const Tester& t, uint32_t i, const BvhTriangle& bt, float tmax, Hit& h) {
    out.push_back({'t', i, tmax, 0, 0, 0});
    return BuiltinUnits::triangle(ray, t, i, bt, tmax, h);
  }
  AvoidanceDecision avoidance(const AvoidanceConfig& cfg, const Ray& ray, uint32_t i, const Triangle& tri,
                              const Hit& h) {
    const AvoidanceDecision d = avoidance_decide(cfg, ray, tri, h);
    if (avoidance_in_use && d.suspect) out.push_back({'a', i, 0, 0, 0, 0});
    return d;
  }
};

}  // namespace

TEST_CASE("a replacement box unit and tester see the nodes and triangles of a hand-traced ray, in order",
          "[module][payload]") {
  const ThreeFloors f;
  Record r;
  r.bvh = &f.bvh;
  r.period_ps = CycleClock(one_slot(3, 5, 11, 7).clock_mhz).period().to_seconds() * 1e12;
  AcceleratorHarness h(f.scene, f.bvh, one_slot(3, 5, 11, 7), ReplayOptions{}, recording_units(r));
  h.run({down_from(7, 1.0f)});
  // Down from z = 1: the root's box (z -2..0); node 0 meets node 1 (entry 1)
  // and the leaf of prim 2 (entry 3): node 1 first; node 1 meets the leaves of
  // prim 0 (entry 1) and prim 1 (entry 2): prim 0's first, whose triangle is
  // hit at t = 1; both pushed entries lie beyond it and are dropped.
  const std::vector<Seen>& seen = r.by_ray.at(0);
  REQUIRE(seen.size() == 4);
  CHECK(seen[0] == Seen{'b', BoxOp::kRootBox, 0, 0, 0, 0});
  CHECK(seen[1] == Seen{'b', 0, 0, 0, 0, 0});
  CHECK(seen[2] == Seen{'b', 1, 0, 0, 0, 0});
  CHECK(seen[3] == Seen{'t', 0, 0, 0, 0, 0});
  for (const Seen& s : seen) {
    CHECK(std::isinf(s.tmax));  // nothing accepted before the last operation
    CHECK(s.ray_id == 7);
    CHECK(s.slot == 0);
  }
  CHECK(r.payload_errors == 0);
  CHECK(h.finished.at(7).prim == 0);
}

TEST_CASE("recording units see exactly the operations of the datapath's traversal, per ray and slot, in order",
          "[module][payload]") {
  const std::string path = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method("validity-bit", opt.method, err));
  auto src = open_trace(path);
  const SceneAndBvh sb = load_trace_scene(src->header());
  src->set_triangle_count(sb.scene.size());
  HwConfig cfg = load_preset("small", "test");
  const uint32_t quantum = GENERATE(1u, 64u, 255u);
  const TlmStyle tlm = GENERATE(TlmStyle::LooselyTimed, TlmStyle::ApproximatelyTimed);
  cfg.quantum_cycles = quantum;
  cfg.memory.tlm = tlm;
  INFO("quantum " << quantum << ", tlm " << tlm_style_name(tlm));

  // The reference: each ray stepped by the datapath alone, in trace order.
  std::vector<TraceRay> rays;
  std::vector<std::vector<Seen>> want;
  std::vector<int32_t> want_prim;
  {
    auto ref_src = open_trace(path);
    ref_src->set_triangle_count(sb.scene.size());
    FunctionalReplayer replayer(sb.scene, sb.bvh, opt);
    BvhStepper<ThreeHalfPlaneTester> stepper(sb.bvh, replayer.filter(), static_cast<int>(cfg.stack_depth));
    const bool in_use = opt.method.validity_bit && opt.method.avoidance.policy != AvoidancePolicy::SignOnly;
    TraceRay tr;
    while (ref_src->next(tr)) {
      rays.push_back(tr);
      const EmittedRay er = replayer.emit(tr);
      std::vector<Seen> seen;
      ReferenceUnits units{seen, in_use};
      CandidateCounters cc;
      TraversalCounters tc;
      StepRequest req = stepper.begin(er.ray, replayer.any_hit(tr, er), cc, tc, units);
      if (sb.bvh.tris.empty()) seen.push_back({'b', BoxOp::kRootBox, er.ray.tmax, 0, 0, 0});
      while (req.kind != StepRequest::Done) {
        if (req.kind == StepRequest::Node) req = stepper.node_step(units);
        else if (req.kind == StepRequest::Refill) req = stepper.refilled();
        else {
          for (uint32_t i = req.index; i < req.index + req.count; ++i)
            if (stepper.triangle_step(i, units).stop) break;
          req = stepper.leaf_done();
        }
      }
      want.push_back(std::move(seen));
      want_prim.push_back(replayer.conclude(tr, er, stepper.hit(), stepper.rejected()).answer);
    }
  }

  Record r;
  r.bvh = &sb.bvh;
  r.period_ps = CycleClock(cfg.clock_mhz).period().to_seconds() * 1e12;
  CycleRunOptions options;
  options.units = recording_units(r);
  std::map<uint64_t, int32_t> got_prim;
  const RayResultSink sink = [&](const TraceRay&, const RayOutcome& out, uint64_t, uint64_t index) {
    got_prim[index] = out.answer;
  };
  const CycleRunResult run =
      run_cycle_replay([&](TraceRay& ray) { return src->next(ray); }, sb.scene, sb.bvh, opt, cfg, sink, options);
  REQUIRE(r.by_ray.size() == rays.size());
  size_t differ = 0, slot_errors = 0, avoidance_ops = 0;
  for (uint64_t i = 0; i < rays.size(); ++i) {
    const std::vector<Seen>& got = r.by_ray.at(i);
    differ += got != want[i] || got_prim.at(i) != want_prim[i];
    for (size_t k = 0; k < got.size(); ++k) {
      // One slot holds the ray from its root box to its end; it is one of its core's.
      slot_errors += got[k].slot != got[0].slot || got[k].core != got[0].core ||
                     got[k].slot / cfg.slots_per_core != got[k].core || got[k].ray_id != rays[i].id;
      if (k < want[i].size()) differ += got[k].tmax != want[i][k].tmax && !(got[k].unit == 'a');
      avoidance_ops += got[k].unit == 'a';
    }
  }
  CHECK(differ == 0);
  CHECK(slot_errors == 0);
  CHECK(r.payload_errors == 0);
  CHECK(avoidance_ops > 0);  // the trace's secondary rays have suspects
  // The scheduler counted every operation of the three replacements.
  CHECK(run.counters.box.ops + run.counters.triangle.ops + run.counters.avoidance.ops == r.calls);
  CHECK(run.counters.box.replaced);

  // When: every call while SystemC time is within the quantum before its cycle.
  CHECK(r.min_ahead >= 0);
  CHECK(r.max_ahead < static_cast<int64_t>(quantum));
  if (quantum == 1) CHECK(r.max_ahead == 0);
  else CHECK(r.max_ahead > 0);  // a quantum of Q does run ahead
}
