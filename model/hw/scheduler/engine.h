// Engine: the scheduler's implementation (hw/scheduler/cycle_engine.h is its
// interface): the event loop that handles a run's events in cycle order, the
// slots, and how a step reaches the units and the memory. `Tester` is the
// triangle tester's datapath type, `Memory` the memory modules' type when every
// core's port reaches a built-in one (L1Cache, IdealMemory) and every unit is
// built-in: reads and unit operations are then direct calls. Otherwise
// MemoryReadIf, and every unit is reached through its interface (PortUnits).
// The ray source's side (dispatch) is defined in engine_dispatch.h, a slot's
// steps in engine_steps.h; hw/scheduler/cycle_engine.cpp instantiates them.
//
// Event ids: slots 0 .. n-1 (a slot's next step), the source's n .. n + S - 1
// (RaySource::event_ids: its lanes, its buffer places), n + S + s for slot
// s resumed after a read whose data came later (a miss whose fill was not known
// when it was found). The memory's steps (hw/memory/memory_clock.h) run before
// the events of their cycle, outside the wheel. Events of one cycle are handled
// in the order they were scheduled (hw/scheduler/event_wheel.h).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "datapath/bvh_stepper.h"
#include "hw/core/pipeline_units.h"
#include "hw/core/ray_test_core.h"
#include "hw/memory/bvh_address_map.h"
#include "hw/memory/ideal_memory.h"
#include "hw/memory/l1_cache.h"
#include "hw/memory/object_caches.h"
#include "hw/scheduler/cycle_engine.h"
#include "hw/scheduler/engine_slot.h"
#include "hw/scheduler/engine_tracer.h"
#include "hw/scheduler/event_wheel.h"
#include "hw/scheduler/port_units.h"
#include "hw/sink/result_sink.h"
#include "hw/source/dispatcher.h"
#include "hw/source/ray_source.h"
#include "hw/unit_pipelines.h"

namespace vbsim::hw::engine_detail {
// The scheduler's code has internal linkage (an unnamed namespace): this header
// and its two companions are included by hw/scheduler/cycle_engine.cpp alone,
// and GCC inlines the steps called from one place (step() into the event loop)
// only into a caller in the same unit with internal linkage; with external
// linkage the cycle bench ran 2.1% more instructions.
namespace {

constexpr uint32_t kMaxSlots = (1u << 23) - 2;

/// The number of slots of `cfg`.
inline uint32_t slot_count(const HwConfig& cfg) {
  const uint64_t slots = uint64_t{cfg.cores} * cfg.slots_per_core;
  if (slots > kMaxSlots) throw std::runtime_error("hw: too many slots");
  return static_cast<uint32_t>(slots);
}

template <class Tester, class Memory>
class Engine final : public CycleEngine, private SourceHost {
 public:
  explicit Engine(const EngineParts& p)
      : cfg_(p.config), replayer_(p.replayer), bvh_(p.bvh), map_(p.bvh, p.config.address_base), source_(p.source),
        dispatcher_(p.dispatcher), builtin_dispatcher_(p.builtin_dispatcher), sink_(p.sink), cores_(p.cores), ideal_(p.builtin_ideal),
        avoidance_in_use_(p.avoidance_in_use), memory_clock_(p.memory_step ? p.memory_clock : &no_memory_work_),
        memory_step_(p.memory_step), tracer_(p.timeline, p.vcd), on_sample_(p.on_sample),
        sample_interval_(p.on_sample ? p.sample_interval : 0), warmup_cycle_(p.on_sample ? p.warmup_cycle : EngineParts::kNoWarmup),
        warmup_rays_(p.on_sample && p.warmup_rays != 0 ? p.warmup_rays : EngineParts::kNoWarmup),
        sampling_(p.on_sample && (p.sample_interval || p.warmup_cycle != EngineParts::kNoWarmup ||
                                  p.warmup_rays != EngineParts::kNoWarmup)) {
    check_traversal_depth(p.bvh);
    ray_times_ = p.ray_times;
    events_.set_fence(memory_clock_->due_address());
    const uint32_t slots = source_id_;  // the slots' ids are 0 .. slots - 1
    for (const CoreBinding& c : cores_) {
      l1s_.push_back(c.core->l1());
      free_count_.push_back(static_cast<uint32_t>(c.core->free_slots.size()));
      if (p.config.controller.count > 0)
        controllers_.emplace_back(UnitConfig{p.config.controller.count, 1, p.config.controller.issue_interval},
                                  c.core->counters.controller, std::string(c.core->name()) + ".controller");
    }
    slots_.reserve(slots);
    for (uint32_t i = 0; i < slots; ++i) {
      slots_.emplace_back(p.bvh, p.replayer.filter(), static_cast<int>(p.config.stack_depth),
                          i / p.config.slots_per_core);
      slots_.back().stepper.set_root_box_test(p.config.root_box_test);
      slots_.back().stepper.set_pop_culling(p.config.pop_culling);
    }
    if (tracing_) tracer_.set_up(cores_, cfg_.slots_per_core, source_id_, &source_);
    if (sampling_) {
      if (p.warmup_rays == 0) warmup_cycle_ = 0;
      next_sample_ = std::min(sample_interval_ ? sample_interval_ : EngineParts::kNoWarmup, warmup_cycle_);
    }
  }

  void start() override { source_.start(*this, 0); }

  void advance(const uint64_t& limit_ref) override {
    for (;;) {
      run_until(limit_ref);
      // Statistics samples: every event before next_sample_ is handled now.
      if (__builtin_expect(!sampling_, 1) || stopped_ || next_sample_ > limit_ref || complete()) return;
      take_sample(next_sample_);
    }
  }
  /// Handles the events before `limit_ref` (read again after each: it may be
  /// lowered meanwhile) and before the next statistics sample. Its one caller
  /// keeps the steps inlined into this loop.
  __attribute__((always_inline)) void run_until(const uint64_t& limit_ref) {
    uint64_t at;
    uint32_t id;
    while (!stopped_) {
      const uint64_t limit = std::min(limit_ref, next_sample_);  // next_sample_: never without samples
      // A memory step runs before the events of its cycle: the wheel opens no
      // cycle at or after it (its fence; the memory's work is always for a
      // later cycle than the one being handled).
      if (!events_.take(limit, at, id)) {
        const uint64_t due = memory_clock_->due();
        if (due >= limit) break;
        run_memory_step(due);
        continue;
      }
      last_handled_ = at;
      const uint32_t next = events_.peek_next();
      if (next < source_id_) slots_[next].prefetch();
      if (id < source_id_) step(id, at);
      else if (id < resumed_id_) source_.on_event(id - source_id_, at);
      else continue_parked(id - resumed_id_, at);
    }
  }
  /// Every event before `cycle` is handled: the statistics sample of `cycle`.
  __attribute__((noinline, cold)) void take_sample(uint64_t cycle) {
    const bool interval = sample_interval_ && cycle > 0 && cycle % sample_interval_ == 0;
    const bool warmup = cycle == warmup_cycle_;
    on_sample_(cycle, interval, warmup);
    if (warmup) warmup_cycle_ = EngineParts::kNoWarmup;
    next_sample_ = sample_interval_ ? cycle - cycle % sample_interval_ + sample_interval_ : EngineParts::kNoWarmup;
    next_sample_ = std::min(next_sample_, warmup_cycle_);
  }
  /// The warm-up by rays ends with this cycle's events (finish() of its last ray).
  __attribute__((noinline, cold)) void warmup_rays_done(uint64_t now) {
    warmup_cycle_ = now + 1;
    next_sample_ = std::min(next_sample_, warmup_cycle_);
  }
  uint64_t last_handled() const override { return last_handled_; }
  bool finished() const override { return stopped_ || (events_.empty() && memory_clock_->due() == kPendingCycle); }
  bool complete() const override { return source_.all_done() && in_flight_ == 0; }
  uint64_t next_event_cycle() const override {
    const uint64_t memory = memory_clock_->due();
    if (events_.empty()) return memory == kPendingCycle ? 0 : memory;
    return std::min(events_.next_cycle(), memory);
  }
  void stop() override { stopped_ = true; }
  bool stopped() const override { return stopped_; }
  uint64_t rays_in_flight() const override { return in_flight_; }
  uint64_t rays_fed() const override { return source_.rays_read(); }
  uint64_t rays_done() const override { return done_; }
  uint64_t waiting_for_memory() const override { return parked_; }
  void resume(uint32_t slot, uint64_t ready) override {
    if (slot >= source_id_ || !slots_[slot].parked || slots_[slot].resumed)
      throw std::runtime_error(fmt::format("{}: an answer (ReadDoneIf::read_done) for slot {}, which waits for no read",
                                           memory_name(slot), slot));
    if (ready < last_handled_)
      throw std::runtime_error(fmt::format(
          "{}: the read of slot {} issued at cycle {} was answered cycle {}, before cycle {} that the accelerator "
          "has reached (ReadDoneIf::read_done must not answer a cycle already handled)",
          memory_name(slot), slot, slots_[slot].requested, ready, last_handled_));
    slots_[slot].resumed = true;
    --parked_;
    events_.schedule(ready, resumed_id_ + slot);  // the step's second half runs at `ready`
  }
  std::string slot_report(size_t max_slots) const override;
  void fast_forward(SampledFeed& feed) override;  // hw/scheduler/engine_fast_forward.h

 private:
  using Slot = EngineSlot<Tester>;
  static_assert(offsetof(Slot, stepper) == 16, "the slot's header is 16 bytes");

  using Unit = EngineTracer::Unit;
  static constexpr Unit kBox = EngineTracer::kBox, kTriangle = EngineTracer::kTriangle,
                        kAvoidance = EngineTracer::kAvoidance;
  static_assert(int{kBox} == int{CoreCounters::kBox} && int{kTriangle} == int{CoreCounters::kTriangle} &&
                    int{kAvoidance} == int{CoreCounters::kAvoidance},
                "the tracer's units in the counters' order");
  static constexpr bool kBuiltinUnits = !std::is_same_v<Memory, MemoryReadIf>;
  // The built-in units' schedules (every unit built-in: kBuiltinUnits).
  __attribute__((always_inline)) static UnitSchedule box_op(const CoreBinding& c, uint64_t ready, uint64_t now) {
    return c.box_builtin->schedule_inline(ready, now);
  }
  __attribute__((always_inline)) static UnitSchedule triangle_op(const CoreBinding& c, uint64_t ready, uint64_t now) {
    return c.triangle_builtin->schedule_inline(ready, now);
  }
  __attribute__((always_inline)) static UnitSchedule avoidance_op(const CoreBinding& c, uint64_t ready,
                                                                  uint64_t now) {
    return c.avoidance_builtin->schedule_inline(ready, now);
  }
  /// Otherwise: the units policy of slot `id`'s next step, its operands ready at `ready`.
  PortUnits<Tester> port_units(const Slot& s, uint32_t id, uint64_t ready, uint64_t now) {
    call_.core = &cores_[s.core];
    call_.from = {s.core, id, s.tr.id, s.trace_index};
    call_.ready = ready;
    call_.now = now;
    call_.box_called = call_.avoidance_called = false;
    call_.low_pool = false;
    return PortUnits<Tester>(call_, avoidance_in_use_);
  }

  /// Slot `id`'s read of `bytes` at `addr`, issued at `now`.
  __attribute__((always_inline)) uint64_t read(const Slot& s, uint32_t id, uint64_t addr, uint32_t bytes,
                                              uint64_t now) {
    if constexpr (std::is_same_v<Memory, L1Cache>) return l1s_[s.core]->read_direct(addr, bytes, now, id);
    else if constexpr (std::is_same_v<Memory, IdealMemory>) return ideal_->read_inline(addr, bytes, now, id);
    else return checked_read(cores_[s.core], id, addr, bytes, now);
  }
  /// The instance answering slot `slot`'s reads (the last core's for a slot out of range), for errors.
  std::string memory_name(uint32_t slot) const {
    const CoreBinding& c = cores_[std::min<size_t>(slot / cfg_.slots_per_core, cores_.size() - 1)];
    return instance_name(c.memory, std::string(c.core->name()) + ".memory");
  }
  /// A read through MemoryReadIf, its answer checked against the interface's contract.
  uint64_t checked_read(const CoreBinding& c, uint32_t id, uint64_t addr, uint32_t bytes, uint64_t now) {
    const uint64_t ready = c.memory->read(addr, bytes, now, id);
    if (ready == kPendingCycle || ready > now) return ready;
    throw std::runtime_error(fmt::format(
        "{}: a read of {} bytes at 0x{:x} issued at cycle {} was answered cycle {}: MemoryReadIf::read must answer "
        "a later cycle (or kPendingCycle)",
        memory_name(id), bytes, addr, now, ready));
  }

  /// Slot `id`'s next step, s.pending, completes at cycle `at` (after its
  /// core's traversal controller has taken it, when the cores have one).
  /// `ended`: the kind of step that has just ended (the controller may take
  /// each kind with its own latency and issue interval, hw.controller.by_step).
  void schedule_step(uint64_t at, uint32_t id, ControllerConfig::Step ended) {
    if (__builtin_expect(!controllers_.empty(), 0))
      at = controllers_[slots_[id].core].issue(at, last_handled_, cfg_.controller.step_interval(ended)) +
           cfg_.controller.step_latency(ended);
    // The step's read looks up its first line's L1 and L2 tag sets when it is
    // handled, many events later: ask the host's caches for them now (no
    // effect on any result). The address by table, not by a branch on the
    // kind (the host mispredicts the kind's sequence): a node's, else the
    // triangles' at the index (for a refill or the end, some triangle's: harmless).
    // The node record itself is not prefetched here: that early, it cost more
    // than it saved (docs/results/speed.md, round 7).
    if constexpr (std::is_same_v<Memory, L1Cache>) {
      const Slot& s = slots_[id];
      const StepRequest& r = s.pending;
      const size_t is_node = r.kind == StepRequest::Node ? 1 : 0;
      l1s_[s.core]->prefetch(model_base_[is_node] + model_stride_[is_node] * r.index);
    }
    events_.schedule(at, id);
  }

  // ---- tracing (VCD and timeline: hw/scheduler/engine_tracer.h; out of line, behind one flag a step) ----

  /// Slot `id`'s step `name` over [start, end), whose read (if any) took [asked, ready).
  __attribute__((noinline, cold)) void trace_step(uint32_t id, const char* name, uint64_t start, uint64_t end,
                                                  uint64_t asked, uint64_t ready) {
    const Slot& s = slots_[id];
    tracer_.step(id, s.core, s.tr.id, name, start, end, asked, ready);
  }
  /// One operation of a unit of slot `id`'s core.
  __attribute__((noinline, cold)) void trace_op(uint32_t id, Unit unit, const UnitSchedule& op) {
    const Slot& s = slots_[id];
    tracer_.op(s.core, s.tr.id, unit, op);
  }

  // ---- ray source and dispatcher (the source's SourceHost; hw/scheduler/engine_dispatch.h) ----

  void schedule_source_event(uint32_t id, uint64_t cycle) override { events_.schedule(cycle, source_id_ + id); }

  bool try_dispatch(const SourceRay& ray, uint64_t at) override;

  /// The dispatcher's choice of a core with a free slot, or -1.
  int pick_core();

  void dispatch(uint32_t core_index, const SourceRay& ray, uint64_t at);

  // ---- a slot's steps (hw/scheduler/engine_steps.h) ----

  void step(uint32_t id, uint64_t now);

  // Each step's part after its read: the read was issued at `asked`, its data
  // are there at `ready`, and the event being handled is at `now`.

  __attribute__((always_inline)) void node_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready, uint64_t now);

  /// Triangle `index` of slot `id`'s leaf through the tester (and the
  /// avoidance unit when it is a suspect), its operands there at `ready`:
  /// `end` grows to its results' cycle; returns the stepper's outcome and, in
  /// `issue`, the cycle the tester took it.
  __attribute__((always_inline)) TriangleStepOutcome test_triangle(Slot& s, const CoreBinding& core, uint32_t id,
                                                                   uint32_t index, uint64_t ready, uint64_t now,
                                                                   uint64_t& end, uint64_t& issue);

  __attribute__((always_inline)) void leaf_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready, uint64_t now);

  /// Per-triangle fetch: the leaf's triangle s.leaf_next has arrived. Its test
  /// issues at once; the next triangle's read starts hw.triangle_fetch_cycles
  /// after its result (and avoidance decision), without passing the traversal
  /// controller; after the last (or a stop) the leaf's end is a step's end.
  void triangle_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready, uint64_t now);

  __attribute__((always_inline)) void refill_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready);

  /// The memory step of cycle `due`, which no event of that cycle has come before.
  __attribute__((noinline)) void run_memory_step(uint64_t due);

  /// The slot's read has no known data cycle yet: it waits for resume().
  void park(Slot& s, uint64_t now);

  /// Parked slot `id`'s data are there at `now` (resume() scheduled it).
  void continue_parked(uint32_t id, uint64_t now);

  void finish(uint32_t id, const CoreBinding& core, uint64_t now);

  const HwConfig& cfg_;
  FunctionalReplayer& replayer_;
  const Bvh& bvh_;
  BvhAddressMap map_;
  RaySourceIf& source_;
  DispatchIf& dispatcher_;
  Dispatcher* builtin_dispatcher_;
  ResultSink& sink_;
  std::vector<CoreBinding> cores_;
  std::vector<L1Cache*> l1s_;         // by core: the built-in L1 (Memory = L1Cache)
  std::vector<uint32_t> free_count_;  // by core: free slots (the dispatcher's view)
  UnitCall call_;                     // the current step's unit call (PortUnits)
  IdealMemory* ideal_;
  bool avoidance_in_use_;
  const bool per_triangle_ = cfg_.per_triangle_fetch;  // hw.triangle_fetch "triangle"
  /// Per node: tested by the low-precision pool (null: no marked nodes or no pool).
  const uint8_t* low_nodes_ =
      cfg_.box_low.count > 0 && !bvh_.low_precision_node.empty() ? bvh_.low_precision_node.data() : nullptr;
  // Per kind (0: a leaf's triangles, 1: a node), the modelled address of record `i`: base + stride * i.
  const uint64_t model_base_[2] = {map_.triangle(0), map_.node(0)};
  const uint64_t model_stride_[2] = {BvhAddressMap::kTriangleBytes, map_.node_bytes};
  const char* node_host_ = bvh_.node_data();  ///< the node records traversal reads (of the tree's width)
  uint32_t source_id_ = slot_count(cfg_);
  uint32_t resumed_id_ = source_id_ + source_.event_ids();
  MemoryClock no_memory_work_;    // the clock without a memory step: never asked for a cycle
  MemoryClock* memory_clock_;
  std::function<void(uint64_t)> memory_step_;
  EventWheel events_{resumed_id_ + source_id_};
  // Sampled simulation (engine_fast_forward.h): the fast-forwarded rays'
  // search, and what their reads warm per core (null where the core's memory
  // is neither a built-in L1 nor object caches: not warmed).
  struct FastForward {
    explicit FastForward(const Bvh& bvh, const CandidateFilter& filter, int depth) : stepper(bvh, filter, depth) {}
    BvhStepper<Tester> stepper;
    std::vector<L1Cache*> l1;
    std::vector<ObjectCaches*> objects;
    uint32_t next_core = 0;
    /// The reads of fast-forwarded rays, kept until the detailed ray after
    /// them is dispatched (the source reads ahead of the rays in flight).
    struct Read {
      uint64_t addr;
      uint32_t bytes, core;
    };
    std::vector<Read> reads;
    /// Runs of `reads`: (source position of the detailed ray after them, end in `reads`).
    std::vector<std::pair<uint64_t, size_t>> runs;
    size_t applied_runs = 0, applied_reads = 0;
  };
  std::unique_ptr<FastForward> fast_forward_;  // made at the first fast_forward()
  bool warm_pending_ = false;                  // fast-forwarded reads wait for a dispatch
  void warm_read(uint32_t core, uint64_t addr, uint32_t bytes);
  /// Warms the caches with the fast-forwarded reads that come before the ray at source position `index`.
  void apply_warm(uint64_t index);
  std::vector<Slot> slots_;
  std::vector<UnitPipelines> controllers_;  ///< per core (hw.controller; empty: none)
  bool stopped_ = false;
  uint64_t in_flight_ = 0, done_ = 0, parked_ = 0, last_handled_ = 0;
  RayTimesSink ray_times_;
  EngineTracer tracer_;
  bool tracing_ = tracer_.on();
  // Statistics samples (EngineParts::on_sample).
  std::function<void(uint64_t, bool, bool)> on_sample_;
  uint64_t sample_interval_ = 0, warmup_cycle_ = EngineParts::kNoWarmup, warmup_rays_ = EngineParts::kNoWarmup;
  bool sampling_ = false;
  uint64_t next_sample_ = EngineParts::kNoWarmup;  ///< the next sample's cycle
};

}  // namespace
}  // namespace vbsim::hw::engine_detail
