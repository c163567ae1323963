// BvhStepper: the closest-hit search of closest_hit.h cut into the steps a
// hardware ray slot performs, so that a timing model can charge each step:
//
//   begin        the root box test (the ray's latched root bounds, no fetch),
//                unless set_root_box_test(false): then the root node is
//                fetched first, as any other (a ray that misses the scene
//                then costs a node fetch and its two box tests)
//   node_step    fetch of node A -> both child box tests -> descend into the
//                nearer child met, push the farther one when both are met;
//                over a 4- or 8-wide tree (Bvh::width) every used slot's box
//                in one operation, the nearest met child descended into and
//                the others pushed farthest first (wide_closest_hit.h)
//   triangle_step  one triangle of the current leaf -> tester -> candidate
//                filter (primid, the avoidance unit); an accepted hit shortens
//                the interval, a rejected one does not
//   leaf_done    after the leaf's triangles: pop the next reachable subtree
//   refilled     after a stack refill read (below)
//
// Each step returns the next request: fetch a node, fetch a leaf's triangles,
// refill the stack from memory, or done. Visiting order, tie breaking and
// counters are those of closest_hit(), so the hit is bit-for-bit the same.
//
// Bounded stack: a slot holds `onchip_depth` stack entries on chip. A push onto
// a full on-chip stack spills its oldest entry to the slot's spill area in
// memory (counted in spills()); a pop that finds the on-chip stack empty while
// spilled entries remain returns a Refill request for the top min(depth, n)
// spilled entries, one read (counted in refills()). The logical stack, and so
// the traversal order, is unchanged; only the timing pays for the overflow.
//
// Units. What the box unit, the triangle tester and the avoidance unit answer
// comes from a units policy passed to each step (begin, node_step,
// triangle_step): BuiltinUnits, the default, computes it with the datapath
// inline (the ray's latched RayBoxTester and Tester, avoidance_decide); a
// timing model passes a policy that asks its unit modules instead
// (hw/stepper_units.h). A policy provides
//
//   bool root_box(const Ray&, const RayBoxTester& latched, const Bounds3f&, float tmax)
//   unsigned node_boxes(const Ray&, const RayBoxTester& latched, uint32_t node,
//                       const BvhNode&, float tmax, float& entry0, float& entry1)
//       bit c set: child c met, entry_c its entry distance (RayBoxTester::hits)
//   template <int W> unsigned wide_node_boxes(const Ray&, const RayBoxTester& latched,
//                       uint32_t node, const WideBvhNode<W>&, float tmax, float* entry)
//       the same for every used slot of a wide node (entry[c] for slot c)
//   unsigned narrow_node_boxes(const Ray&, const RayBoxTester& latched, const NarrowBoxTester&,
//                       uint32_t node, const BvhNode&, float tmax, float& entry0, float& entry1)
//       a node Bvh::low_precision_node marks, in the narrow format
//       (Bvh::narrow_mantissa_bits >= 0: rtcore-systemc's low-precision test)
//   bool triangle(const Ray&, const Tester& latched, uint32_t index,
//                 const BvhTriangle&, float tmax, Hit&)      (the tester contract)
//   AvoidanceDecision avoidance(const AvoidanceConfig&, const Ray&, uint32_t index,
//                               const Triangle&, const Hit&)  (avoidance_decide's)
//
// and the stepper keeps the visiting order, tie breaking and counters whatever
// the answers: a policy that answers as the datapath does gives closest_hit()'s
// hit bit for bit.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>

#include "datapath/candidate_filter.h"
#include "datapath/closest_hit.h"
#include "datapath/hit.h"
#include "datapath/narrow_box_tester.h"
#include "datapath/ray.h"
#include "datapath/ray_box_tester.h"
#include "scene/bvh.h"

namespace vbsim {

struct StepRequest {
  enum Kind : uint32_t { Node, Leaf, Refill, Done };  // 32 bits: a request returns in two registers
  Kind kind = Done;
  uint32_t index = 0;  ///< Node: node index; Leaf: first triangle; Refill: first stack entry to read
  uint32_t count = 0;  ///< Leaf: triangles; Refill: entries to read
};

/// What one triangle step saw.
struct TriangleStepOutcome {
  bool candidate = false;  ///< the tester reported a hit inside the interval
  bool suspect = false;    ///< the avoidance unit found equal sign and front/back bits
  bool accepted = false;   ///< became the closest hit so far
  bool stop = false;       ///< any-hit search: the ray is finished
};

/// The datapath's own answers, inlined (no call leaves the step).
struct BuiltinUnits {
  static bool root_box(const Ray&, const RayBoxTester& latched, const Bounds3f& b, float tmax) {
    return latched.hits(b, tmax);
  }
  static unsigned node_boxes(const Ray&, const RayBoxTester& latched, uint32_t, const BvhNode& n, float tmax,
                             float& entry0, float& entry1) {
    return latched.hits(n, tmax, entry0, entry1);
  }
  template <int W>
  static unsigned wide_node_boxes(const Ray&, const RayBoxTester& latched, uint32_t, const WideBvhNode<W>& n,
                                  float tmax, float* entry) {
    return latched.hits(n, tmax, entry);
  }
  static unsigned narrow_node_boxes(const Ray&, const RayBoxTester&, const NarrowBoxTester& narrow, uint32_t,
                                    const BvhNode& n, float tmax, float& entry0, float& entry1) {
    return narrow.hits(n, tmax, entry0, entry1);
  }
  template <class Tester>
  static bool triangle(const Ray&, const Tester& latched, uint32_t, const BvhTriangle& bt, float tmax, Hit& h) {
    return latched.intersect(bt.tri, tmax, h);
  }
  static AvoidanceDecision avoidance(const AvoidanceConfig& cfg, const Ray& ray, uint32_t, const Triangle& tri,
                                     const Hit& h) {
    return avoidance_decide(cfg, ray, tri, h);
  }
};

template <class Tester>
class BvhStepper {
 public:
  /// Bytes of one stack entry in the spill area (node/leaf reference and entry distance).
  static constexpr uint32_t kEntryBytes = 16;

  /// `bvh` and `filter` must outlive the stepper; onchip_depth >= 1.
  BvhStepper(const Bvh& bvh, const CandidateFilter& filter, int onchip_depth)
      : bvh_(&bvh), onchip_depth_(onchip_depth < 1 ? 1 : onchip_depth), narrow_on_(bvh.narrow_nodes()),
        filter_(&filter) {}

  /// Latches `ray` and tests the root box. Counters go to `cc` and `tc`
  /// (which must outlive the search).
  template <class Units = BuiltinUnits>
  StepRequest begin(const Ray& ray, bool any_hit, CandidateCounters& cc, TraversalCounters& tc, Units&& units = {}) {
    ray_ = ray;
    any_hit_ = any_hit;
    cc_ = &cc;
    tc_ = &tc;
    best_ = Hit{};
    tmax_ = ray.tmax;
    sp_ = onchip_ = 0;
    rejected_ = spills_ = refills_ = 0;
    finished_ = false;
    if (bvh_->tris.empty()) return done();  // an empty scene: nothing is read or counted
    tester_.emplace(ray_);
    box_.emplace(ray_);
    if (__builtin_expect(narrow_on_, 0)) narrow_.emplace(ray_, bvh_->narrow_mantissa_bits);
    if (!root_box_test_) return visit(bvh_->root);
    ++tc.box_tests;
    if (!units.root_box(ray_, *box_, bvh_->root_bounds, cull_limit(tmax_))) return done();
    return visit(bvh_->root);
  }

  /// Both child boxes of the current node (the request was Node).
  template <class Units = BuiltinUnits>
  StepRequest node_step(Units&& units = {}) {
    if (__builtin_expect(bvh_->width != 2, 0)) return bvh_->width == 4 ? wide_node_step<4>(units) : wide_node_step<8>(units);
    const BvhNode& n = bvh_->nodes[current_.index];
    ++tc_->node_visits;
    tc_->box_tests += 2;
    if (__builtin_expect(narrow_on_, 0)) return narrow_node_step(units, n);
    float t0, t1;
    const unsigned hit = units.node_boxes(ray_, *box_, current_.index, n, cull_limit(tmax_), t0, t1) & 3u;
    return descend(n, hit, t0, t1);
  }

  /// Triangle `i` (an index in Bvh::tris inside the current leaf, taken in order).
  template <class Units = BuiltinUnits>
  TriangleStepOutcome triangle_step(uint32_t i, Units&& units = {}) {
    TriangleStepOutcome out;
    const BvhTriangle& bt = bvh_->tris[i];
    ++tc_->triangle_tests;
    Hit h;
    if (!units.triangle(ray_, *tester_, i, bt, candidate_limit(best_, tmax_), h)) return out;
    h.prim = static_cast<int32_t>(bt.prim);
    if (!nearer_than_best(h, best_, tmax_)) return out;  // a tie with a lower id already held (closest_hit.h)
    out.candidate = true;
    const uint64_t suspects_before = cc_->suspects;
    const bool accept = filter_->accept(ray_, bt.tri, h.prim, h, *cc_, [&](const AvoidanceConfig& cfg) {
      return units.avoidance(cfg, ray_, i, bt.tri, h);
    });
    out.suspect = cc_->suspects != suspects_before;
    if (!accept) {
      ++rejected_;
      return out;
    }
    out.accepted = true;
    best_ = h;
    tmax_ = h.t;
    if (any_hit_) out.stop = finished_ = true;
    return out;
  }

  /// After the current leaf's triangles (or after a triangle step that stopped).
  StepRequest leaf_done() { return finished_ ? done() : pop(); }

  /// After the Refill read: the entries it named are on chip again.
  StepRequest refilled() {
    onchip_ = refill_count_;
    return pop();
  }

  const Hit& hit() const { return best_; }
  const Ray& ray() const { return ray_; }  ///< the latched ray
  float tmax() const { return tmax_; }     ///< the interval's end now (the closest accepted hit's t)
  uint64_t rejected() const { return rejected_; }  ///< candidates the filter rejected for this ray
  uint64_t spills() const { return spills_; }      ///< entries pushed past the on-chip depth
  uint64_t refills() const { return refills_; }    ///< refill reads
  int onchip_depth() const { return onchip_depth_; }
  /// Whether begin() tests the root's box (true, the default) or goes straight
  /// to the root (the hit is the same; the work is not).
  void set_root_box_test(bool on) { root_box_test_ = on; }
  bool root_box_test() const { return root_box_test_; }
  /// Whether a popped subtree whose entry lies beyond the closest hit so far
  /// is skipped (true, the default) or visited all the same, its boxes and
  /// triangles tested against the hit (the hit is the same; the work is not).
  void set_pop_culling(bool on) { pop_culling_ = on; }
  /// Host bytes of the traversal stack, the stepper's last member (a timing
  /// model may prefetch the stepper's other members before a step).
  static constexpr size_t stack_host_bytes() { return sizeof(Entry) * (kTraversalStackDepth + 1); }
  /// Host bytes from the stepper's start that node_step() reads (pop() reads
  /// its stack too): the scalars, then the box tester's two-child state.
  static constexpr size_t node_step_host_bytes() {
    return offsetof(BvhStepper, box_) + RayBoxTester::two_child_host_bytes();
  }

 private:
  StepRequest done() {
    finished_ = true;
    return {StepRequest::Done, 0, 0};
  }

  /// A node step of the W-wide tree (wide_closest_hit.h's order): every used
  /// slot's box in one operation, the nearest met child descended into, the
  /// other met children pushed farthest first (each push spills the oldest
  /// on-chip entry when the on-chip stack is full).
  template <int W, class Units>
  __attribute__((noinline)) StepRequest wide_node_step(Units& units) {  // out of line: the binary step stays lean
    const WideBvhNode<W>& n = wide_nodes<W>(*bvh_)[current_.index];
    ++tc_->node_visits;
    tc_->box_tests += n.children;
    alignas(16) float entry[W];
    const unsigned met = units.wide_node_boxes(ray_, *box_, current_.index, n, cull_limit(tmax_), entry) &
                         ((1u << n.children) - 1u);
    if (met == 0u) return pop();
    int order[W];
    const int k = wide_visit_order(met, entry, order);
    for (int i = k - 1; i >= 1; --i) {
      stack_[sp_++] = {n.ref[order[i]], n.count[order[i]], entry[order[i]]};
      ++tc_->stack_pushes;
      if (onchip_ == onchip_depth_) ++spills_;
      else ++onchip_;
    }
    return visit(n.child(order[0]));
  }

  /// A binary node step's second half: descend into the nearer child met,
  /// push the farther when both are (`hit`: bit c, child c met at entry t_c).
  __attribute__((always_inline)) StepRequest descend(const BvhNode& n, unsigned hit, float t0, float t1) {
    if (hit == 0u) return pop();
    // One or both children met: descend into the nearer (child 0 on a tie),
    // push the farther when both are met. Written without branches on the
    // box results (the host mispredicts them about half the time): the
    // farther entry is always written at the top and kept only when pushed.
    const unsigned both = (hit >> 1) & hit & 1u;
    const unsigned child1_nearer = t0 <= t1 ? 0u : 1u;
    const unsigned first = (hit >> 1) & (((hit & 1u) ^ 1u) | child1_nearer);  // hit 2: 1; 1: 0; 3: by entry
    const float entry[2] = {t0, t1};
    const BvhRef near = n.child(static_cast<int>(first)), far = n.child(static_cast<int>(first ^ 1u));
    stack_[sp_] = {far.index, far.count, entry[first ^ 1u]};
    const unsigned full = onchip_ == onchip_depth_ ? 1u : 0u;
    sp_ += static_cast<int>(both);
    tc_->stack_pushes += both;
    spills_ += both & full;                        // the oldest on-chip entry goes to memory
    onchip_ += static_cast<int>(both & (full ^ 1u));
    return visit(near);
  }

  /// A binary node step in a tree whose low-precision nodes are tested in the
  /// narrow format (Bvh::narrow_mantissa_bits): out of line, so that the
  /// float32 step stays as it is.
  template <class Units>
  __attribute__((noinline)) StepRequest narrow_node_step(Units& units, const BvhNode& n) {
    float t0, t1;
    const unsigned hit =
        (bvh_->low_precision_node[current_.index]
             ? units.narrow_node_boxes(ray_, *box_, *narrow_, current_.index, n, cull_limit(tmax_), t0, t1)
             : units.node_boxes(ray_, *box_, current_.index, n, cull_limit(tmax_), t0, t1)) &
        3u;
    return descend(n, hit, t0, t1);
  }

  /// Node: {Node, index, 0} (an interior node's count is 0); leaf: {Leaf, first, count}.
  StepRequest visit(BvhRef r) {
    current_ = r;
    return {static_cast<StepRequest::Kind>(r.is_leaf() ? StepRequest::Leaf : StepRequest::Node), r.index, r.count};
  }

  /// The next subtree the ray can still reach before its closest hit.
  StepRequest pop() {
    for (;;) {
      if (sp_ == 0) return done();
      if (onchip_ == 0) {
        refill_count_ = sp_ < onchip_depth_ ? sp_ : onchip_depth_;
        ++refills_;
        return {StepRequest::Refill, static_cast<uint32_t>(sp_ - refill_count_),
                static_cast<uint32_t>(refill_count_)};
      }
      --sp_;
      --onchip_;
      ++tc_->stack_pops;
      if (pop_culling_ && stack_[sp_].t > cull_limit(tmax_)) continue;
      return visit(BvhRef{stack_[sp_].index, stack_[sp_].count});
    }
  }

  struct Entry {
    uint32_t index, count;
    float t;
  };

  // What node_step and pop use first, side by side (a timing model interleaves
  // many steppers, so each step finds them in as few host cache lines as
  // possible): the scalars in 44 bytes (a timing model's slot puts its 16-byte
  // header before them, so the two share one 64-byte line), then the box
  // tester's vectors; then what the triangle steps and the ray's end use.
  const Bvh* bvh_;
  TraversalCounters* tc_ = nullptr;
  float tmax_ = 0.0f;
  BvhRef current_;
  int sp_ = 0, onchip_ = 0;
  int onchip_depth_;
  uint32_t spills_ = 0;  // a ray's spills are fewer than its node visits
  std::optional<RayBoxTester> box_;
  int refill_count_ = 0;
  bool finished_ = false;
  bool any_hit_ = false;
  bool root_box_test_ = true;
  bool pop_culling_ = true;
  bool narrow_on_;  ///< the tree's low-precision nodes are tested narrow (Bvh::narrow_nodes; narrow_ holds the ray's test)
  const CandidateFilter* filter_;
  CandidateCounters* cc_ = nullptr;
  Hit best_;
  uint64_t rejected_ = 0, refills_ = 0;
  Ray ray_;
  std::optional<Tester> tester_;
  std::optional<NarrowBoxTester> narrow_;  ///< with narrow low-precision nodes (begin() latches it)
  // Last: a step touches only its top, the rest stays cold. One spare entry:
  // node_step writes the entry above the top even when it does not push.
  Entry stack_[kTraversalStackDepth + 1];
};

}  // namespace vbsim
