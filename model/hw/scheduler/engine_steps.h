// Engine (hw/scheduler/engine.h): a slot's steps. Each step reads its data
// through the core's memory port (a node, a leaf's triangles, a stack refill)
// and hands them to the core's units (box unit; triangle tester and, for a
// suspect, the avoidance unit); the step's end schedules the slot's next one.
// A read whose data come later parks the slot until resume().
#pragma once
#include "hw/scheduler/engine.h"

namespace vbsim::hw::engine_detail {
namespace {

template <class Tester, class Memory>
inline void Engine<Tester, Memory>::step(uint32_t id, uint64_t now) {
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

template <class Tester, class Memory>
inline void Engine<Tester, Memory>::node_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready, uint64_t now) {
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

template <class Tester, class Memory>
inline TriangleStepOutcome Engine<Tester, Memory>::test_triangle(Slot& s, const CoreBinding& core, uint32_t id, uint32_t index, uint64_t ready, uint64_t now, uint64_t& end, uint64_t& issue) {
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

template <class Tester, class Memory>
inline void Engine<Tester, Memory>::leaf_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready, uint64_t now) {
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

template <class Tester, class Memory>
inline void Engine<Tester, Memory>::triangle_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready, uint64_t now) {
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

template <class Tester, class Memory>
inline void Engine<Tester, Memory>::refill_arrived(Slot& s, const CoreBinding& core, uint32_t id, uint64_t asked, uint64_t ready) {
  CoreCounters& cc = core.core->counters;
  ++cc.refill_reads;
  cc.refill_wait_cycles += ready - asked;
  if (__builtin_expect(tracing_, 0)) trace_step(id, "refill", asked, ready, asked, ready);
  s.pending = s.stepper.refilled();
  schedule_step(ready, id, ControllerConfig::Refill);
}

template <class Tester, class Memory>
void Engine<Tester, Memory>::run_memory_step(uint64_t due) {
  if (due < last_handled_) throw std::logic_error("hw: a memory step for a cycle already handled");
  memory_clock_->take(due);
  last_handled_ = due;
  memory_step_(due);
}

template <class Tester, class Memory>
inline void Engine<Tester, Memory>::park(Slot& s, uint64_t now) {
  s.parked = true;
  s.resumed = false;
  s.requested = now;
  ++parked_;
}

template <class Tester, class Memory>
inline void Engine<Tester, Memory>::continue_parked(uint32_t id, uint64_t now) {
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

template <class Tester, class Memory>
inline void Engine<Tester, Memory>::finish(uint32_t id, const CoreBinding& core, uint64_t now) {
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
  if (__builtin_expect(tracing_, 0)) tracer_.occupancy(s.core, now, -1);
  if (ray_times_)
    ray_times_({s.trace_index, s.tr.id, s.tr.parent, s.ready, s.emitted, s.dispatched, now, s.core,
                id - cores_[s.core].core->first_slot(), s.entered});
  source_.on_finish(s.trace_index, now);  // its children's wait and the window move on
  source_.on_slot_free(now);              // a held ray takes the slot
}

}  // namespace
}  // namespace vbsim::hw::engine_detail
