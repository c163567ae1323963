#include "hw/cycle_engine.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "datapath/bvh_stepper.h"
#include "datapath/testers.h"
#include "hw/bvh_address_map.h"
#include "hw/dispatcher.h"
#include "hw/event_wheel.h"
#include "hw/ideal_memory.h"
#include "hw/l1_cache.h"
#include "hw/pipeline_units.h"
#include "hw/port_units.h"
#include "hw/ray_source.h"
#include "hw/ray_test_core.h"
#include "hw/result_sink.h"
#include "hw/unit_pipelines.h"

#include <systemc>

namespace vbsim::hw {

namespace {

// Event ids: slots 0 .. n-1 (a slot's next step), the source's n .. n + S - 1
// (RaySource::event_ids: its lanes, its buffer places), n + S + s for slot
// s resumed after a read whose data came later (a miss whose fill was not known
// when it was found). The memory's steps (hw/memory_clock.h) run before the
// events of their cycle, outside the wheel.
// Events of one cycle are handled in the order they were scheduled
// (hw/event_wheel.h).
constexpr uint32_t kMaxSlots = (1u << 23) - 2;

/// The number of slots of `cfg`.
uint32_t slot_count(const HwConfig& cfg) {
  const uint64_t slots = uint64_t{cfg.cores} * cfg.slots_per_core;
  if (slots > kMaxSlots) throw std::runtime_error("hw: too many slots");
  return static_cast<uint32_t>(slots);
}

/// `Memory` is the memory modules' type when every core's port reaches a
/// built-in one (L1Cache, IdealMemory) and every unit is built-in: reads and
/// unit operations are then direct calls. Otherwise MemoryReadIf, and every
/// unit is reached through its interface.
template <class Tester, class Memory>
class Engine final : public CycleEngine, private SourceHost {
 public:
  explicit Engine(const EngineParts& p)
      : cfg_(p.config), replayer_(p.replayer), bvh_(p.bvh), map_(p.bvh, p.config.address_base), source_(p.source),
        dispatcher_(p.dispatcher), builtin_dispatcher_(p.builtin_dispatcher), sink_(p.sink), cores_(p.cores), ideal_(p.builtin_ideal),
        avoidance_in_use_(p.avoidance_in_use), memory_clock_(p.memory_step ? p.memory_clock : &no_memory_work_),
        memory_step_(p.memory_step), timeline_(p.timeline), vcd_(p.vcd), on_sample_(p.on_sample),
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
    if (tracing_) set_up_tracing();
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
      if (next < source_id_) prefetch_slot(slots_[next]);
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
    bool parked = false;       ///< its read's data are not known yet (resume() continues it)
    bool resumed = false;      ///< parked, and resume() has scheduled its continuation
    uint64_t requested = 0;    ///< parked: the cycle its read was issued
    uint64_t ready = 0, emitted = 0;  ///< when the ray was ready for emission and its emission started
    uint64_t entered = 0;             ///< when it entered the source's buffer
    /// Per-triangle fetch (hw.triangle_fetch "triangle"): the leaf's next triangle to read.
    uint32_t leaf_next = 0;
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

  enum Unit { kBox = CoreCounters::kBox, kTriangle = CoreCounters::kTriangle, kAvoidance = CoreCounters::kAvoidance,
              kUnits };
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

  // ---- tracing (VCD and timeline; out of line, behind one flag a step) ----

  /// Per core: the VCD signal (operations in flight) and timeline track of each
  /// unit, its busy-slot signal and its memory's track.
  struct CoreTrace {
    uint32_t unit_signal[kUnits], unit_track[kUnits];
    uint32_t busy_signal, memory_track;
    uint32_t reads_signal;  ///< reads of its slots issued, data not yet there
  };
  static const char* instance_name(sc_core::sc_interface* iface, const std::string& fallback) {
    const auto* o = dynamic_cast<const sc_core::sc_object*>(iface);
    return o ? o->name() : fallback.c_str();
  }
  void set_up_tracing() {
    static const char* kSignal = "ops_in_flight";
    for (const CoreBinding& c : cores_) {
      const std::string core = c.core->name();
      const std::string units[kUnits] = {instance_name(c.box, core + ".box_unit"),
                                         instance_name(c.triangle, core + ".triangle_tester"),
                                         instance_name(c.avoidance, core + ".avoidance_unit")};
      CoreTrace t{};
      for (int u = 0; u < kUnits; ++u) {
        t.unit_signal[u] = vcd_ ? vcd_->signal(units[u], kSignal) : VcdRecorder::kNoSignal;
        const std::string thread = units[u].substr(units[u].rfind('.') + 1);
        t.unit_track[u] = timeline_ ? timeline_->track(core, thread, units[u]) : TimelineRecorder::kNoTrack;
      }
      t.busy_signal = vcd_ ? vcd_->signal(core, "busy_slots") : VcdRecorder::kNoSignal;
      t.reads_signal = vcd_ ? vcd_->signal(core, "reads_in_flight") : VcdRecorder::kNoSignal;
      t.memory_track = timeline_ ? timeline_->track(core, "memory reads") : TimelineRecorder::kNoTrack;
      core_trace_.push_back(t);
    }
    if (timeline_)
      for (uint32_t i = 0; i < source_id_; ++i)
        slot_track_.push_back(timeline_->track(cores_[i / cfg_.slots_per_core].core->name(),
                                               "slot " + std::to_string(i % cfg_.slots_per_core)));
    if (vcd_) {
      rays_done_signal_ = vcd_->signal("accelerator", "rays_done");
      in_flight_signal_ = vcd_->signal("accelerator", "rays_in_flight");
      const std::string source = instance_name(&source_, "accelerator.ray_source");
      source_waiting_signal_ = vcd_->signal(source, "rays_waiting");
      source_emitted_signal_ = vcd_->signal(source, "rays_emitted");
    }
  }
  /// A ray that entered the source's buffer at `entered`, was emitted (its
  /// emission started) at `emitted` and left for a slot at `at`.
  __attribute__((noinline, cold)) void trace_source(uint64_t entered, uint64_t emitted, uint64_t at) {
    if (!vcd_) return;
    vcd_->add(source_waiting_signal_, entered, +1);
    vcd_->add(source_waiting_signal_, at, -1);
    vcd_->add(source_emitted_signal_, emitted, +1);
  }
  /// Slot `id`'s step `name` over [start, end), whose read (if any) took [asked, ready).
  __attribute__((noinline, cold)) void trace_step(uint32_t id, const char* name, uint64_t start, uint64_t end,
                                                  uint64_t asked, uint64_t ready) {
    const Slot& s = slots_[id];
    if (vcd_ && ready > asked) {
      vcd_->add(core_trace_[s.core].reads_signal, asked, +1);
      vcd_->add(core_trace_[s.core].reads_signal, ready, -1);
    }
    if (!timeline_) return;
    timeline_->add(slot_track_[id], name, start, end, s.tr.id);
    if (ready > asked) timeline_->add(core_trace_[s.core].memory_track, name, asked, ready, s.tr.id);
  }
  /// One operation of a unit of core `core`.
  __attribute__((noinline, cold)) void trace_op(uint32_t id, Unit unit, const UnitSchedule& op) {
    static const char* kNames[kUnits] = {"box", "triangle", "avoidance"};
    const Slot& s = slots_[id];
    const CoreTrace& t = core_trace_[s.core];
    if (vcd_) {
      vcd_->add(t.unit_signal[unit], op.issue, +1);
      vcd_->add(t.unit_signal[unit], op.done, -1);
    }
    if (timeline_) timeline_->add(t.unit_track[unit], kNames[unit], op.issue, op.done, s.tr.id);
  }
  /// A ray entering (+1) or leaving (-1) a slot of core `core` at `at`.
  __attribute__((noinline, cold)) void trace_occupancy(uint32_t core, uint64_t at, int delta) {
    if (!vcd_) return;
    vcd_->add(core_trace_[core].busy_signal, at, delta);
    vcd_->add(in_flight_signal_, at, delta);
    if (delta < 0) vcd_->add(rays_done_signal_, at, 1);
  }

  // ---- ray source and dispatcher (the source's SourceHost) ----

  void schedule_source_event(uint32_t id, uint64_t cycle) override { events_.schedule(cycle, source_id_ + id); }

  bool try_dispatch(const SourceRay& ray, uint64_t at) override {
    const int core = pick_core();
    if (core < 0) return false;
    dispatch(static_cast<uint32_t>(core), ray, at);
    return true;
  }

  /// The dispatcher's choice of a core with a free slot, or -1.
  int pick_core() {
    const uint32_t n = static_cast<uint32_t>(cores_.size());
    if (builtin_dispatcher_) return builtin_dispatcher_->Dispatcher::pick(free_count_.data(), n);
    const int core = dispatcher_.pick(free_count_.data(), n);
    if (core >= 0 ? core < static_cast<int>(n) && free_count_[core] > 0 : core == -1) return core;
    throw std::runtime_error(fmt::format(
        "{}: DispatchIf::pick chose core {}, which {}: it must choose a core with a free slot, or -1 (none)",
        instance_name(&dispatcher_, "dispatcher"), core,
        core >= 0 && core < static_cast<int>(n) ? "has no free slot"
                                                : fmt::format("does not exist (the accelerator has {} cores)", n)));
  }

  void dispatch(uint32_t core_index, const SourceRay& ray, uint64_t at) {
    const CoreBinding& core = cores_[core_index];
    std::vector<uint32_t>& free = core.core->free_slots;
    const uint32_t id = free.back();
    free.pop_back();
    --free_count_[core_index];
    ++in_flight_;
    Slot& s = slots_[id];
    s.tr = ray.tr;
    s.trace_index = ray.index;
    s.er = ray.er;
    s.dispatched = at;
    s.ready = ray.ready;
    s.emitted = ray.emitted;
    s.entered = ray.entered;
    KindStats& ks = replayer_.stats().by_kind[static_cast<int>(s.tr.kind)];
    // The root box test: bounds latched with the ray (hw.root_box_test; off:
    // the root node's fetch follows the dispatch at once).
    UnitSchedule box{at, at};
    const bool root_test = cfg_.root_box_test;
    if constexpr (kBuiltinUnits) {
      s.pending = s.stepper.begin(s.er.ray, replayer_.any_hit(s.tr, s.er), ks.candidates, ks.traversal);
      if (root_test) box = box_op(core, at, at);
    } else {
      PortUnits<Tester> units = port_units(s, id, at, at);
      s.pending = s.stepper.begin(s.er.ray, replayer_.any_hit(s.tr, s.er), ks.candidates, ks.traversal, units);
      if (root_test && !call_.box_called) {  // an empty scene: the root's (empty) box is still tested
        const RayBoxTester latched(s.er.ray);
        units.root_box(s.er.ray, latched, bvh_.root_bounds, s.er.ray.tmax);
      }
      if (root_test) box = call_.box;
    }
    if (__builtin_expect(tracing_, 0)) {
      trace_occupancy(core_index, at, +1);
      trace_source(ray.entered, ray.emitted, at);
      if (root_test) {
        trace_step(id, "root box", box.issue, box.done, 0, 0);
        trace_op(id, kBox, box);
      }
    }
    schedule_step(box.done, id, ControllerConfig::Start);
  }

  // ---- a slot's steps ----

  void step(uint32_t id, uint64_t now) {
    Slot& s = slots_[id];
    const CoreBinding& core = cores_[s.core];
    switch (s.pending.kind) {
      case StepRequest::Node: {
        // The box test below waits for the node record: ask for it before the
        // memory model's work, so that the two overlap on the host.
        __builtin_prefetch(node_host_ + size_t{s.pending.index} * map_.node_bytes);
        const uint64_t ready = read(s, id, map_.node(s.pending.index), map_.node_bytes, now);
        if (__builtin_expect(ready == kPendingCycle, 0)) return park(s, now);
        return node_arrived(s, core, id, now, ready, now);
      }
      case StepRequest::Leaf: {
        if (__builtin_expect(per_triangle_, 0)) {
          const uint64_t ready =
              read(s, id, map_.triangle(s.pending.index + s.leaf_next), BvhAddressMap::kTriangleBytes, now);
          if (__builtin_expect(ready == kPendingCycle, 0)) return park(s, now);
          return triangle_arrived(s, core, id, now, ready, now);
        }
        const uint64_t ready =
            read(s, id, map_.triangle(s.pending.index), s.pending.count * BvhAddressMap::kTriangleBytes, now);
        if (__builtin_expect(ready == kPendingCycle, 0)) return park(s, now);
        return leaf_arrived(s, core, id, now, ready, now);
      }
      case StepRequest::Refill: {
        const uint64_t ready = read(s, id, map_.stack_entry(id, s.pending.index),
                                    s.pending.count * BvhAddressMap::kStackEntryBytes, now);
        if (__builtin_expect(ready == kPendingCycle, 0)) return park(s, now);
        return refill_arrived(s, core, id, now, ready);
      }
      case StepRequest::Done:
        finish(id, core, now);
        return;
    }
  }

  // Each step's part after its read: the read was issued at `asked`, its data
  // are there at `ready`, and the event being handled is at `now`.

  __attribute__((always_inline)) void node_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready, uint64_t now) {
    CoreCounters& cc = core.core->counters;
    ++cc.node_fetches;
    cc.memory_wait_cycles += ready - asked;
    // Both children low-precision (bvh.low_precision) and a pool for them (hw.box_low).
    const bool low = low_nodes_ && low_nodes_[s.pending.index];
    UnitSchedule box;
    if constexpr (kBuiltinUnits) {
      box = low ? core.box_low->schedule_inline(ready, now) : box_op(core, ready, now);
      s.pending = s.stepper.node_step();
    } else {
      PortUnits<Tester> units = port_units(s, id, ready, now);
      call_.low_pool = low;
      s.pending = s.stepper.node_step(units);
      box = call_.box;
    }
    if (__builtin_expect(tracing_, 0)) {
      trace_step(id, "node", asked, box.done, asked, ready);
      trace_op(id, kBox, box);
    }
    schedule_step(box.done, id, ControllerConfig::Node);
  }

  /// Triangle `index` of slot `id`'s leaf through the tester (and the
  /// avoidance unit when it is a suspect), its operands there at `ready`:
  /// `end` grows to its results' cycle; returns the stepper's outcome and, in
  /// `issue`, the cycle the tester took it.
  __attribute__((always_inline)) TriangleStepOutcome test_triangle(Slot& s, const CoreBinding& core, uint32_t id,
                                                                   uint32_t index, uint64_t ready, uint64_t now,
                                                                   uint64_t& end, uint64_t& issue) {
    UnitSchedule tri;
    TriangleStepOutcome out;
    bool avoidance = false;
    if constexpr (kBuiltinUnits) {
      tri = triangle_op(core, ready, now);
      out = s.stepper.triangle_step(index);
      avoidance = out.suspect && avoidance_in_use_;
    } else {
      out = s.stepper.triangle_step(index, port_units(s, id, ready, now));
      tri = call_.triangle;
      avoidance = call_.avoidance_called;
    }
    issue = tri.issue;
    end = std::max(end, tri.done);
    if (__builtin_expect(tracing_, 0)) trace_op(id, kTriangle, tri);
    if (avoidance) {
      const UnitSchedule a = kBuiltinUnits ? avoidance_op(core, tri.done, now) : call_.avoidance;
      ++core.core->counters.avoidance_ops_by_kind[static_cast<int>(s.tr.kind)];
      if (__builtin_expect(tracing_, 0)) trace_op(id, kAvoidance, a);
      end = std::max(end, a.done);
    }
    return out;
  }

  __attribute__((always_inline)) void leaf_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready, uint64_t now) {
    CoreCounters& cc = core.core->counters;
    const uint32_t first = s.pending.index, count = s.pending.count;
    ++cc.leaf_fetches;
    cc.memory_wait_cycles += ready - asked;
    uint64_t end = ready, next_ready = ready;
    for (uint32_t i = 0; i < count; ++i) {
      uint64_t issue = 0;
      const TriangleStepOutcome out = test_triangle(s, core, id, first + i, next_ready, now, end, issue);
      next_ready = issue + 1;  // a slot hands its pipelines one triangle per cycle
      if (out.stop) break;
    }
    if (__builtin_expect(tracing_, 0)) trace_step(id, "leaf", asked, end, asked, ready);
    s.pending = s.stepper.leaf_done();
    schedule_step(end, id, ControllerConfig::Leaf);
  }

  /// Per-triangle fetch: the leaf's triangle s.leaf_next has arrived. Its test
  /// issues at once; the next triangle's read starts hw.triangle_fetch_cycles
  /// after its result (and avoidance decision), without passing the traversal
  /// controller; after the last (or a stop) the leaf's end is a step's end.
  void triangle_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready, uint64_t now) {
    CoreCounters& cc = core.core->counters;
    cc.leaf_fetches += s.leaf_next == 0;
    cc.memory_wait_cycles += ready - asked;
    uint64_t end = ready, issue = 0;
    const TriangleStepOutcome out = test_triangle(s, core, id, s.pending.index + s.leaf_next, ready, now, end, issue);
    if (__builtin_expect(tracing_, 0)) trace_step(id, "leaf", asked, end, asked, ready);
    if (!out.stop && ++s.leaf_next < s.pending.count) return events_.schedule(end + cfg_.triangle_fetch_cycles, id);
    s.leaf_next = 0;
    s.pending = s.stepper.leaf_done();
    schedule_step(end, id, ControllerConfig::Leaf);
  }

  __attribute__((always_inline)) void refill_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready) {
    CoreCounters& cc = core.core->counters;
    ++cc.refill_reads;
    cc.refill_wait_cycles += ready - asked;
    if (__builtin_expect(tracing_, 0)) trace_step(id, "refill", asked, ready, asked, ready);
    s.pending = s.stepper.refilled();
    schedule_step(ready, id, ControllerConfig::Refill);
  }

  /// The memory step of cycle `due`, which no event of that cycle has come before.
  __attribute__((noinline)) void run_memory_step(uint64_t due) {
    if (due < last_handled_) throw std::logic_error("hw: a memory step for a cycle already handled");
    memory_clock_->take(due);
    last_handled_ = due;
    memory_step_(due);
  }

  /// The slot's read has no known data cycle yet: it waits for resume().
  void park(Slot& s, uint64_t now) {
    s.parked = true;
    s.resumed = false;
    s.requested = now;
    ++parked_;
  }

  /// Parked slot `id`'s data are there at `now` (resume() scheduled it).
  void continue_parked(uint32_t id, uint64_t now) {
    Slot& s = slots_[id];
    const CoreBinding& core = cores_[s.core];
    s.parked = false;
    switch (s.pending.kind) {
      case StepRequest::Node: return node_arrived(s, core, id, s.requested, now, now);
      case StepRequest::Leaf:
        return per_triangle_ ? triangle_arrived(s, core, id, s.requested, now, now)
                             : leaf_arrived(s, core, id, s.requested, now, now);
      case StepRequest::Refill: return refill_arrived(s, core, id, s.requested, now);
      case StepRequest::Done: return finish(id, core, now);
    }
  }

  void finish(uint32_t id, const CoreBinding& core, uint64_t now) {
    Slot& s = slots_[id];
    sink_.ray_done(s.tr, s.er, s.stepper.hit(), s.stepper.rejected(), s.dispatched, now, s.trace_index);
    CoreCounters& cc = core.core->counters;
    cc.slot_cycles += now - s.dispatched;
    ++cc.rays;
    cc.spills += s.stepper.spills();
    --in_flight_;
    ++done_;
    if (__builtin_expect(done_ == warmup_rays_, 0)) warmup_rays_done(now);
    core.core->free_slots.push_back(id);
    ++free_count_[s.core];
    if (__builtin_expect(tracing_, 0)) trace_occupancy(s.core, now, -1);
    if (ray_times_)
      ray_times_({s.trace_index, s.tr.id, s.tr.parent, s.ready, s.emitted, s.dispatched, now, s.core,
                  id - cores_[s.core].core->first_slot(), s.entered});
    source_.on_finish(s.trace_index, now);  // its children's wait and the window move on
    source_.on_slot_free(now);              // a held ray takes the slot
  }

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
  MemoryClock no_memory_work_{0};  // the clock without a memory step: never asked for a cycle
  MemoryClock* memory_clock_;
  std::function<void(uint64_t)> memory_step_;
  EventWheel events_{resumed_id_ + source_id_};
  std::vector<Slot> slots_;
  std::vector<UnitPipelines> controllers_;  ///< per core (hw.controller; empty: none)
  bool stopped_ = false;
  uint64_t in_flight_ = 0, done_ = 0, parked_ = 0, last_handled_ = 0;
  RayTimesSink ray_times_;
  TimelineRecorder* timeline_;
  VcdRecorder* vcd_;
  bool tracing_ = timeline_ || vcd_;
  std::vector<CoreTrace> core_trace_;
  // Statistics samples (EngineParts::on_sample).
  std::function<void(uint64_t, bool, bool)> on_sample_;
  uint64_t sample_interval_ = 0, warmup_cycle_ = EngineParts::kNoWarmup, warmup_rays_ = EngineParts::kNoWarmup;
  bool sampling_ = false;
  uint64_t next_sample_ = EngineParts::kNoWarmup;  ///< the next sample's cycle
  std::vector<uint32_t> slot_track_;
  uint32_t rays_done_signal_ = VcdRecorder::kNoSignal, in_flight_signal_ = VcdRecorder::kNoSignal;
  uint32_t source_waiting_signal_ = VcdRecorder::kNoSignal, source_emitted_signal_ = VcdRecorder::kNoSignal;
};

template <class Tester, class Memory>
std::string Engine<Tester, Memory>::slot_report(size_t max_slots) const {
  static const char* kinds[] = {"node", "leaf", "refill", "done"};
  std::ostringstream out;
  size_t shown = 0;
  for (uint32_t id = 0; id < slots_.size(); ++id) {
    const std::vector<uint32_t>& free = cores_[slots_[id].core].core->free_slots;
    if (std::find(free.begin(), free.end(), id) != free.end()) continue;
    if (shown++ == max_slots) {
      out << "  ...\n";
      break;
    }
    const Slot& s = slots_[id];
    out << "  " << cores_[s.core].core->name() << " slot " << id - cores_[s.core].core->first_slot() << ": ray "
        << s.tr.id << " (trace position " << s.trace_index << "), dispatched at cycle " << s.dispatched << ", next step "
        << kinds[s.pending.kind] << " " << s.pending.index;
    if (s.parked) out << ", waiting since cycle " << s.requested << " for a read";
    out << "\n";
  }
  out << source_.buffer_report();
  return out.str();
}

template <class Tester>
std::unique_ptr<CycleEngine> make_for_tester(const EngineParts& p) {
  bool builtin_units = true;
  for (const CoreBinding& c : p.cores)
    builtin_units &= c.box_builtin && c.triangle_builtin && c.avoidance_builtin;
  if (builtin_units && p.builtin_l1s) return std::make_unique<Engine<Tester, L1Cache>>(p);
  if (builtin_units && p.builtin_ideal) return std::make_unique<Engine<Tester, IdealMemory>>(p);
  return std::make_unique<Engine<Tester, MemoryReadIf>>(p);
}

}  // namespace

std::unique_ptr<CycleEngine> make_cycle_engine(const EngineParts& p) {
  switch (p.replayer.options().tester) {
    case TesterKind::MollerTrumbore: return make_for_tester<MollerTrumboreTester>(p);
    case TesterKind::PbrtWatertight: return make_for_tester<PbrtWatertightTester>(p);
    case TesterKind::ThreeHalfPlane:
    default: return make_for_tester<ThreeHalfPlaneTester>(p);
  }
}

}  // namespace vbsim::hw
