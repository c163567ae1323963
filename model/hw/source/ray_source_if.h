// Part contract (hw/source/): the ray source and the dispatcher, the front of
// the patent's FIG. 12. It reads rays from the feed (a trace, or a closed-loop
// shader: hw/source/ray_feed.h), holds them until their parent has finished,
// emits each through the datapath (the method's emission-time work and the
// parent sign bit) and hands it to a core with a free slot. It is called only
// by the scheduler (hw/scheduler/); it may call the datapath, the feed and the
// scheduler's SourceHost, never a core, the memory or the sink.
//
// RaySourceIf: the ray source as the scheduler reaches it (hw/source/ray_source.h is
// the built-in one, the patent's ray-emission interface). A module implementing
// it can take the built-in source's place (AcceleratorUnits::ray_source): it
// reads its rays from the feed it is given, emits each through the datapath
// (FunctionalReplayer::emit, in trace order) and hands it to the dispatcher
// through SourceHost::try_dispatch at a cycle of its choosing, at or after the
// event being handled; it learns when each of its rays finishes and when a slot
// frees. Its events are the ids [0, event_ids()), each scheduled through
// SourceHost::schedule_source_event for a cycle at or after the one being
// handled; the scheduler calls on_event(id, cycle) then. Calls come in time
// order (docs/hw-model.md, "When a unit is called").
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

#include <systemc>

#include "hw/source/ray_feed.h"
#include "replay/functional_replayer.h"
#include "trace/trace_record.h"

namespace vbsim::hw {

/// One buffered ray as the source hands it to the dispatcher.
struct SourceRay {
  TraceRay tr;
  EmittedRay er;
  uint64_t index = 0;   ///< position in the trace (0 for the first ray)
  uint64_t ready = 0;   ///< cycle it became ready for emission
  uint64_t emitted = 0; ///< cycle its emission started
  uint64_t entered = 0; ///< cycle it entered the buffer
};

/// What the source needs from the scheduler.
class SourceHost {
 public:
  virtual ~SourceHost() = default;
  /// The source's event `id` (0 <= id < RaySource::event_ids()) fires at `cycle`.
  virtual void schedule_source_event(uint32_t id, uint64_t cycle) = 0;
  /// Puts `ray` in a free slot at `at`; false when every slot is busy.
  virtual bool try_dispatch(const SourceRay& ray, uint64_t at) = 0;
};

class RaySourceIf : public virtual sc_core::sc_interface {
 public:
  /// The rays to emit, in trace order (set before the simulation starts).
  virtual void set_feed(RayFeed feed) = 0;
  /// A closed-loop feed in place of a trace (RayShader::next_ray): asked at
  /// the cycle a ray is wanted; after Later, asked again once a ray finishes.
  /// A source that takes none throws std::logic_error (the default).
  virtual void set_shader_feed(ShaderFeed) {
    throw std::logic_error("this ray source takes no closed-loop feed (RaySourceIf::set_shader_feed)");
  }
  /// Event ids the source uses, 0 .. event_ids() - 1 (fixed once it is built).
  virtual uint32_t event_ids() const = 0;
  /// The run starts at cycle `at`; `host` outlives the run.
  virtual void start(SourceHost& host, uint64_t at) = 0;
  /// Event `id`, scheduled through SourceHost::schedule_source_event, fires at `at`.
  virtual void on_event(uint32_t id, uint64_t at) = 0;
  /// The ray it dispatched with trace position `index` finished at `at`.
  virtual void on_finish(uint64_t index, uint64_t at) = 0;
  /// A slot became free at `at` (a dispatch refused earlier may succeed now).
  virtual void on_slot_free(uint64_t at) = 0;
  /// The feed has ended and every ray read has finished.
  virtual bool all_done() const = 0;
  /// Rays read from the feed so far.
  virtual uint64_t rays_read() const = 0;
  /// Rays it holds not yet dispatched, for the report of a stuck run.
  virtual std::string buffer_report() const { return {}; }
};

}  // namespace vbsim::hw
