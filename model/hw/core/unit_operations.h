// The operations a ray-test core hands its box unit, triangle tester and
// intersection-avoidance unit (hw/unit_interfaces.h), and what each answers:
// the schedule (when it issues, when its result is there) and the result
// itself, which the slot's BvhStepper acts on. Every pointer in an operation
// is valid for the call only.
//
// Time is in cycles of the accelerator's clock from the run's start: `ready`
// is when the operands are there (>= now), `now` the cycle of the event being
// handled (unit_interfaces.h says when, in SystemC time, that call happens).
// An answer must have issue >= ready and done >= issue; the scheduler checks
// it and stops the run with an error naming the unit otherwise.
#pragma once
#include <cstdint>

#include "datapath/avoidance_unit.h"
#include "datapath/hit.h"
#include "datapath/narrow_box_tester.h"
#include "datapath/ray.h"
#include "datapath/ray_box_tester.h"
#include "datapath/triangle.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim::hw {

/// When one operation of a pipelined unit issues and when its result is there.
struct UnitSchedule {
  uint64_t issue;  ///< cycle the operation enters a pipeline (>= its ready cycle)
  uint64_t done;   ///< cycle its result is available (>= issue)
};

/// Who asks: the same in every operation.
struct OpSource {
  uint32_t core = 0;          ///< the core's index
  uint32_t slot = 0;          ///< the accelerator-wide slot id (core c's are [c R, (c+1) R))
  int64_t ray_id = 0;         ///< the trace's ray id
  uint64_t trace_index = 0;   ///< the ray's position in the trace (0: the first ray)
};

/// One box-unit operation: the root's box at dispatch (node == kRootBox,
/// `root` set, every record null), or every child box of interior node `node`:
/// of a binary tree both (`node_record` = &Bvh::nodes[node]), of a 4-wide
/// (8-wide) tree every used slot (`node4_record` = &Bvh::nodes4[node], or
/// `node8_record` = &Bvh::nodes8[node]). One record at most is set.
struct BoxOp {
  static constexpr uint32_t kRootBox = ~uint32_t{0};
  OpSource from;
  uint32_t node = kRootBox;
  const BvhNode* node_record = nullptr;
  const BvhNode4* node4_record = nullptr;
  const BvhNode8* node8_record = nullptr;
  /// With node_record: a node Bvh::low_precision_node marks, in a tree whose
  /// marked nodes are tested in the narrow format (Bvh::narrow_mantissa_bits
  /// >= 0): the ray's latched narrow test, which the answer must follow.
  const NarrowBoxTester* narrow = nullptr;
  const Bounds3f* root = nullptr;
  const Ray* ray = nullptr;               ///< the ray as the slot holds it
  const RayBoxTester* latched = nullptr;  ///< the ray's latched box-test state (o, 1/d, tmin)
  /// The bound to cull at: the ray's tmax, or once it holds a hit, that hit's
  /// t widened as a box's exit is (datapath/closest_hit.h, cull_limit).
  float tmax = 0.0f;
  uint64_t ready = 0, now = 0;
};

/// Bit c of `met`: child (slot) c's box is met (the root test: bit 0, the
/// root's box); entry[c]: where the ray enters it (read only when met, and only
/// for nodes). Bits of unused slots are ignored.
struct BoxAnswer {
  UnitSchedule schedule{0, 0};
  unsigned met = 0;
  alignas(16) float entry[8];  // not cleared: read only where met
};

/// One triangle test: triangle `index` of Bvh::tris (scene triangle `prim`).
struct TriangleOp {
  OpSource from;
  uint32_t index = 0;
  int32_t prim = 0;
  const Triangle* triangle = nullptr;
  const Ray* ray = nullptr;
  /// The bound to test against: the ray's tmax, or once the slot holds a hit,
  /// that hit's t widened by a few ulps, so that a tie is seen (the stepper
  /// then keeps the lower primitive id; datapath/closest_hit.h, candidate_limit).
  float tmax = 0.0f;
  uint64_t ready = 0, now = 0;
};

/// The tester contract (datapath/testers.h): `candidate` when the ray meets the
/// triangle at ray.tmin < t < tmax; then hit.t, hit.u, hit.v and hit.front
/// (the front/back bit: 1 when dot(d, Ng) < 0) are set (hit.prim is ignored).
struct TriangleAnswer {
  UnitSchedule schedule{0, 0};
  bool candidate = false;
  Hit hit;
};

/// One suspect candidate for the avoidance unit: the ray's parent sign bit
/// equals the tester's front/back bit (validity-bit method, a policy that tests).
struct AvoidanceOp {
  OpSource from;
  uint32_t index = 0;  ///< the candidate's triangle in Bvh::tris
  const Hit* candidate = nullptr;
  const Triangle* triangle = nullptr;
  const Ray* ray = nullptr;
  uint8_t sign_bit = 0;   ///< the ray's parent sign bit (ray->sign)
  uint8_t front = 0;      ///< the tester's front/back bit (candidate->front)
  const AvoidanceConfig* config = nullptr;  ///< policy, epsilons, enabled tests
  uint64_t ready = 0, now = 0;
};

/// `decision.reject`: the candidate is dropped (the search goes on with its
/// interval unchanged); `invalid` says which epsilon tests said "too close"
/// (counted in the statistics). `decision.suspect` is taken as true.
struct AvoidanceAnswer {
  UnitSchedule schedule{0, 0};
  AvoidanceDecision decision;
};

}  // namespace vbsim::hw
