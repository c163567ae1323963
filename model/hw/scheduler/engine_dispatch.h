// Engine (hw/scheduler/engine.h): the ray source's side of the scheduler
// (SourceHost): the dispatcher's choice of a core and a ray's entry into one
// of its slots, with its root box test.
#pragma once
#include "hw/scheduler/engine.h"

namespace vbsim::hw::engine_detail {
namespace {

template <class Tester, class Memory>
inline bool Engine<Tester, Memory>::try_dispatch(const SourceRay& ray, uint64_t at) {
  const int core = pick_core();
  if (core < 0) return false;
  dispatch(static_cast<uint32_t>(core), ray, at);
  return true;
}

template <class Tester, class Memory>
inline int Engine<Tester, Memory>::pick_core() {
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

template <class Tester, class Memory>
inline void Engine<Tester, Memory>::dispatch(uint32_t core_index, const SourceRay& ray, uint64_t at) {
  const CoreBinding& core = cores_[core_index];
  std::vector<uint32_t>& free = core.core->free_slots;
  const uint32_t id = free.back();
  free.pop_back();
  --free_count_[core_index];
  ++in_flight_;
  Slot& s = slots_[id];
  if (__builtin_expect(warm_pending_, 0)) apply_warm(ray.index);  // a sampled run's fast-forwarded reads before it
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
    tracer_.occupancy(core_index, at, +1);
    tracer_.source_ray(ray.entered, ray.emitted, at);
    if (root_test) {
      trace_step(id, "root box", box.issue, box.done, 0, 0);
      trace_op(id, kBox, box);
    }
  }
  schedule_step(box.done, id, ControllerConfig::Start);
}

}  // namespace
}  // namespace vbsim::hw::engine_detail
