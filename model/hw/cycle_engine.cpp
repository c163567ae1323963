#include "hw/cycle_engine.h"

#include <algorithm>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "datapath/bvh_stepper.h"
#include "datapath/testers.h"
#include "hw/bvh_address_map.h"
#include "hw/event_wheel.h"
#include "hw/memory_hierarchy.h"
#include "hw/unit_pipelines.h"

namespace vbsim::hw {

namespace {

// Event ids: slots 0 .. n-1, the source n. Events of one cycle are handled in
// the order they were scheduled (hw/event_wheel.h).
constexpr uint32_t kMaxSlots = (1u << 24) - 2;

/// The number of event ids for `cfg`: its slots and the source.
uint32_t event_ids(const HwConfig& cfg) {
  const uint64_t slots = uint64_t{cfg.cores} * cfg.slots_per_core;
  if (slots > kMaxSlots) throw std::runtime_error("hw: too many slots");
  return static_cast<uint32_t>(slots + 1);
}

/// Running totals of every core's pipelines, by kind.
struct UnitTotals {
  UnitCounters box, triangle, avoidance;
};

struct Core {
  Core(const HwConfig& c, UnitTotals& t) : box(c.box, t.box), tri(c.triangle, t.triangle), avoid(c.avoidance, t.avoidance) {}
  UnitPipelines box, tri, avoid;
  std::vector<uint32_t> free_slots;  ///< global slot ids
};

/// Emission-time method operations acting on `tr` (each costs emission_op_cycles).
uint32_t emission_ops(const SelfIntersectionMethod& m, const TraceRay& tr) {
  const bool child = tr.parent_prim >= 0, shadow = tr.kind == RayKind::Shadow;
  uint32_t ops = m.tmin;
  if (child) ops += m.offset_normal + m.offset_direction + m.offset_adaptive + m.offset_errbound;
  if (shadow && child) ops += m.shading_position || m.shading_position_always;
  if (shadow) ops += m.reverse_shadow;
  return ops;
}

/// `Memory` is the port's concrete type when the engine knows it (IdealMemory,
/// MemoryHierarchy: their reads are then direct calls), else MemoryPort.
template <class Tester, class Memory>
class Engine final : public CycleEngine {
 public:
  Engine(const HwConfig& cfg, FunctionalReplayer& replayer, const Bvh& bvh, Memory& memory, RayFeed feed,
         RayResultSink sink)
      : cfg_(cfg), replayer_(replayer), bvh_(bvh), memory_(memory), map_(bvh, cfg.address_base), feed_(std::move(feed)),
        sink_(std::move(sink)),
        avoidance_in_use_(replayer.options().method.validity_bit &&
                          replayer.options().method.avoidance.policy != AvoidancePolicy::SignOnly) {
    check_traversal_depth(bvh);
    const uint32_t slots = source_id_;
    cores_.reserve(cfg.cores);
    for (uint32_t c = 0; c < cfg.cores; ++c) {
      cores_.emplace_back(cfg, unit_totals_);
      for (uint32_t s = cfg.slots_per_core; s-- > 0;) cores_.back().free_slots.push_back(c * cfg.slots_per_core + s);
    }
    slots_.reserve(slots);
    for (uint32_t i = 0; i < slots; ++i)
      slots_.emplace_back(bvh, replayer.filter(), static_cast<int>(cfg.stack_depth), i / cfg.slots_per_core);
    counters_.latency_histogram.assign(cfg.latency_buckets, 0);
    start_emission(0);
  }

  void advance(uint64_t limit) override {
    uint64_t at;
    uint32_t id;
    while (!stopped_ && events_.take(limit, at, id)) {
      const uint32_t next = events_.peek_next();
      if (next < source_id_) prefetch_slot(slots_[next]);
      if (id == source_id_) source_ready(at);
      else step(id, at);
    }
  }
  bool finished() const override { return stopped_ || events_.empty(); }
  uint64_t next_event_cycle() const override { return events_.empty() ? 0 : events_.next_cycle(); }
  void stop() override { stopped_ = true; }
  bool stopped() const override { return stopped_; }
  const HwCounters& counters() const override { return counters_; }
  uint64_t rays_in_flight() const override { return in_flight_; }
  void set_timeline_window(uint64_t first, uint64_t cycles, std::vector<TimelineEvent>* out) override {
    tl_first_ = first;
    tl_end_ = first + cycles;
    timeline_ = out;
  }

 private:
  // 64-byte aligned: a step's first host cache line holds the slot's core and
  // request and the stepper's scalars.
  struct alignas(64) Slot {
    Slot(const Bvh& bvh, const CandidateFilter& filter, int depth, uint32_t core_index)
        : core(core_index), stepper(bvh, filter, depth) {}
    uint32_t core;  ///< the core holding this slot
    StepRequest pending;
    BvhStepper<Tester> stepper;  // its traversal stack at its end
    uint64_t dispatched = 0;
    uint64_t trace_index = 0;  ///< the ray's position in the feed
    TraceRay tr;
    EmittedRay er;
    /// Bytes from the slot's start that a node step reads: the header (core,
    /// request) and the stepper up to its box tester (3 host lines). Leaf steps
    /// read further; prefetching those lines for every step cost more than it
    /// saved (docs/results/speed.md, round 9).
    static constexpr size_t kNodeStepBytes = 16 + BvhStepper<Tester>::node_step_host_bytes();
  };
  static_assert(offsetof(Slot, stepper) == 16, "the slot's header is 16 bytes");

  /// Asks the host's caches for the part of `s` a node step uses.
  static void prefetch_slot(const Slot& s) {
    const char* p = reinterpret_cast<const char*>(&s);
    for (size_t at = 0; at < Slot::kNodeStepBytes; at += 64) __builtin_prefetch(p + at);
  }

  /// Slot `id`'s next step, s.pending, completes at cycle `at`.
  void schedule_step(uint64_t at, uint32_t id) {
    // The step's read looks up its first line's L1 and L2 tag sets when it is
    // handled, many events later: ask the host's caches for them now (no
    // effect on any result). The address by table, not by a branch on the
    // kind (the host mispredicts the kind's sequence): a node's, else the
    // triangles' at the index (for a refill or the end, some triangle's: harmless).
    // The node record itself is not prefetched here: that early, it cost more
    // than it saved (docs/results/speed.md, round 7).
    if constexpr (std::is_same_v<Memory, MemoryHierarchy>) {
      const Slot& s = slots_[id];
      const StepRequest& r = s.pending;
      const size_t is_node = r.kind == StepRequest::Node ? 1 : 0;
      memory_.prefetch(static_cast<int>(s.core), model_base_[is_node] + model_stride_[is_node] * r.index);
    }
    events_.schedule(at, id);
  }

  void record(const char* name, uint32_t id, uint64_t start, uint64_t end) {
    if (!timeline_ || start < tl_first_ || start >= tl_end_) return;
    timeline_->push_back({name, id / cfg_.slots_per_core, id % cfg_.slots_per_core, start, end, slots_[id].tr.id});
  }

  // ---- ray source and dispatcher ----

  /// The source starts emitting the next trace ray at cycle `at`.
  void start_emission(uint64_t at) {
    if (!feed_(next_tr_)) return;  // end of the trace
    next_index_ = fed_++;
    next_er_ = replayer_.emit(next_tr_);
    uint64_t cost = cfg_.source.issue_interval;
    if (next_tr_.sign < 0 && next_tr_.parent_prim >= 0) {
      cost += cfg_.source.sign_bit_cycles;
      ++counters_.sign_bits_computed;
    }
    const uint32_t ops = emission_ops(replayer_.options().method, next_tr_);
    counters_.emission_ops += ops;
    cost += uint64_t{ops} * cfg_.source.emission_op_cycles;
    counters_.source_busy_cycles += cost;
    events_.schedule(at + cost, source_id_);
  }

  /// The emitted ray is ready at `at`: dispatch it, or hold it until a slot frees.
  void source_ready(uint64_t at) {
    Core* core = pick_core();
    if (!core) {
      blocked_ = true;
      blocked_since_ = at;
      return;
    }
    dispatch(*core, at);
    start_emission(at);
  }

  Core* pick_core() {
    const uint32_t n = cfg_.cores;
    if (cfg_.dispatch == DispatchPolicy::RoundRobin) {
      for (uint32_t k = 0; k < n; ++k) {
        const uint32_t c = (rr_next_ + k) % n;
        if (!cores_[c].free_slots.empty()) {
          rr_next_ = (c + 1) % n;
          return &cores_[c];
        }
      }
      return nullptr;
    }
    Core* best = nullptr;
    for (Core& c : cores_)
      if (!c.free_slots.empty() && (!best || c.free_slots.size() > best->free_slots.size())) best = &c;
    return best;
  }

  void dispatch(Core& core, uint64_t at) {
    const uint32_t id = core.free_slots.back();
    core.free_slots.pop_back();
    ++in_flight_;
    Slot& s = slots_[id];
    s.tr = next_tr_;
    s.trace_index = next_index_;
    s.er = next_er_;
    s.dispatched = at;
    KindStats& ks = replayer_.stats().by_kind[static_cast<int>(s.tr.kind)];
    s.pending = s.stepper.begin(s.er.ray, replayer_.any_hit(s.tr, s.er), ks.candidates, ks.traversal);
    const uint64_t issue = core.box.issue(at, at);  // the root box test: bounds latched with the ray
    record("box", id, issue, issue + core.box.latency());
    schedule_step(issue + core.box.latency(), id);
  }

  // ---- a slot's steps ----

  void step(uint32_t id, uint64_t now) {
    Slot& s = slots_[id];
    Core& core = cores_[s.core];
    const int core_index = static_cast<int>(s.core);
    switch (s.pending.kind) {
      case StepRequest::Node: {
        // The box test below waits for the node record: ask for it before the
        // memory model's work, so that the two overlap on the host.
        __builtin_prefetch(&bvh_.nodes[s.pending.index]);
        const uint64_t ready = memory_.read(core_index, map_.node(s.pending.index), BvhAddressMap::kNodeBytes, now);
        ++counters_.node_fetches;
        counters_.memory_wait_cycles += ready - now;
        const uint64_t issue = core.box.issue(ready, now);
        const uint64_t end = issue + core.box.latency();
        record("node", id, now, end);
        s.pending = s.stepper.node_step();
        schedule_step(end, id);
        return;
      }
      case StepRequest::Leaf: {
        const uint32_t first = s.pending.index, count = s.pending.count;
        const uint64_t ready = memory_.read(core_index, map_.triangle(first), count * BvhAddressMap::kTriangleBytes, now);
        ++counters_.leaf_fetches;
        counters_.memory_wait_cycles += ready - now;
        uint64_t end = ready, next_ready = ready;
        for (uint32_t i = 0; i < count; ++i) {
          const uint64_t issue = core.tri.issue(next_ready, now);
          next_ready = issue + 1;  // a slot hands its pipelines one triangle per cycle
          const uint64_t result = issue + core.tri.latency();
          end = std::max(end, result);
          const TriangleStepOutcome out = s.stepper.triangle_step(first + i);
          if (out.suspect && avoidance_in_use_) {
            const uint64_t a = core.avoid.issue(result, now);
            ++counters_.avoidance_ops_by_kind[static_cast<int>(s.tr.kind)];
            record("avoidance", id, a, a + core.avoid.latency());
            end = std::max(end, a + core.avoid.latency());
          }
          if (out.stop) break;
        }
        record("leaf", id, now, end);
        s.pending = s.stepper.leaf_done();
        schedule_step(end, id);
        return;
      }
      case StepRequest::Refill: {
        const uint64_t ready = memory_.read(core_index, map_.stack_entry(id, s.pending.index),
                                            s.pending.count * BvhAddressMap::kStackEntryBytes, now);
        ++counters_.refill_reads;
        counters_.refill_wait_cycles += ready - now;
        record("refill", id, now, ready);
        s.pending = s.stepper.refilled();
        schedule_step(ready, id);
        return;
      }
      case StepRequest::Done:
        finish(id, core, now);
        return;
    }
  }

  void finish(uint32_t id, Core& core, uint64_t now) {
    Slot& s = slots_[id];
    const RayOutcome out = replayer_.conclude(s.tr, s.er, s.stepper.hit(), s.stepper.rejected());
    if (sink_) sink_(s.tr, out, now, s.trace_index);
    HwCounters& c = counters_;
    const uint64_t latency = now - s.dispatched;
    c.slot_cycles += latency;
    c.latency_min = c.rays == 0 ? latency : std::min(c.latency_min, latency);
    c.latency_max = std::max(c.latency_max, latency);
    const uint64_t bucket = std::min<uint64_t>(latency / cfg_.latency_bucket_cycles, c.latency_histogram.size() - 1);
    ++c.latency_histogram[bucket];
    ++c.rays;
    c.cycles = now;
    c.spills += s.stepper.spills();
    c.box = unit_totals_.box;
    c.triangle = unit_totals_.triangle;
    c.avoidance = unit_totals_.avoidance;
    --in_flight_;
    core.free_slots.push_back(id);
    if (blocked_) {  // the source's held ray takes a slot now
      blocked_ = false;
      c.no_free_slot_cycles += now - blocked_since_;
      dispatch(*pick_core(), now);
      start_emission(now);
    }
  }

  const HwConfig cfg_;
  FunctionalReplayer& replayer_;
  const Bvh& bvh_;
  Memory& memory_;
  BvhAddressMap map_;
  RayFeed feed_;
  RayResultSink sink_;
  bool avoidance_in_use_;
  // Per kind (0: a leaf's triangles, 1: a node), the modelled address of record `i`: base + stride * i.
  const uint64_t model_base_[2] = {map_.triangle(0), map_.node(0)};
  const uint64_t model_stride_[2] = {BvhAddressMap::kTriangleBytes, BvhAddressMap::kNodeBytes};
  std::vector<Core> cores_;
  EventWheel events_{event_ids(cfg_)};
  uint32_t source_id_ = event_ids(cfg_) - 1;
  UnitTotals unit_totals_;
  std::vector<Slot> slots_;
  TraceRay next_tr_;
  uint64_t next_index_ = 0, fed_ = 0;  // the held ray's trace index; rays read from the feed
  EmittedRay next_er_;
  bool blocked_ = false, stopped_ = false;
  uint64_t blocked_since_ = 0, in_flight_ = 0;
  uint32_t rr_next_ = 0;
  HwCounters counters_;
  std::vector<TimelineEvent>* timeline_ = nullptr;
  uint64_t tl_first_ = 0, tl_end_ = 0;
};

template <class Tester>
std::unique_ptr<CycleEngine> make_for_tester(const HwConfig& cfg, FunctionalReplayer& replayer, const Bvh& bvh,
                                             MemoryPort& memory, RayFeed feed, RayResultSink sink) {
  if (auto* ideal = dynamic_cast<IdealMemory*>(&memory))
    return std::make_unique<Engine<Tester, IdealMemory>>(cfg, replayer, bvh, *ideal, std::move(feed),
                                                         std::move(sink));
  if (auto* caches = dynamic_cast<MemoryHierarchy*>(&memory))
    return std::make_unique<Engine<Tester, MemoryHierarchy>>(cfg, replayer, bvh, *caches, std::move(feed),
                                                             std::move(sink));
  return std::make_unique<Engine<Tester, MemoryPort>>(cfg, replayer, bvh, memory, std::move(feed), std::move(sink));
}

}  // namespace

std::unique_ptr<CycleEngine> make_cycle_engine(const HwConfig& cfg, FunctionalReplayer& replayer, const Bvh& bvh,
                                               MemoryPort& memory, RayFeed feed, RayResultSink sink) {
  switch (replayer.options().tester) {
    case TesterKind::MollerTrumbore:
      return make_for_tester<MollerTrumboreTester>(cfg, replayer, bvh, memory, std::move(feed), std::move(sink));
    case TesterKind::PbrtWatertight:
      return make_for_tester<PbrtWatertightTester>(cfg, replayer, bvh, memory, std::move(feed), std::move(sink));
    case TesterKind::ThreeHalfPlane:
    default:
      return make_for_tester<ThreeHalfPlaneTester>(cfg, replayer, bvh, memory, std::move(feed), std::move(sink));
  }
}

}  // namespace vbsim::hw
