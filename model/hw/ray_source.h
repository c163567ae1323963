// RaySource: the patent's ray-emission interface (FIG. 12) in front of the
// dispatcher. It reads the next trace ray, runs the ray-emission step of the
// datapath (FunctionalReplayer::emit: the origin, emission-time methods such as
// offsets and tmin, and the parent sign bit when the trace lacks it) and hands
// the emitted ray record on when its emission cycles are over:
//   source.issue_interval
//   + sign_bit_cycles      when a child ray's sign bit must be computed
//   + emission_op_cycles   per emission-time method operation acting on the ray
// It emits one ray at a time; a ready ray waits here while every slot is busy.
#pragma once
#include <cstdint>

#include <systemc>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/ray_feed.h"
#include "hw/stat_provider.h"
#include "hw/unit_interfaces.h"

namespace vbsim::hw {

class RaySource final : public sc_core::sc_module, public RaySourceIf, public StatProvider {
 public:
  sc_core::sc_export<RaySourceIf> target;

  /// `replayer` outlives the source.
  RaySource(sc_core::sc_module_name name, const SourceConfig& config, FunctionalReplayer& replayer);
  /// The trace to emit (before the simulation starts).
  void set_feed(RayFeed feed) { feed_ = std::move(feed); }

  bool start_emission(uint64_t at, uint64_t& ready) final;
  const TraceRay& trace_ray() const override { return tr_; }
  const EmittedRay& emitted_ray() const override { return er_; }
  uint64_t trace_index() const override { return index_; }
  void held(uint64_t since, uint64_t now) override { counters_.no_free_slot_cycles += now - since; }

  const SourceCounters& counters() const { return counters_; }
  const char* unit_kind() const override { return "RaySource"; }
  nlohmann::json parameters() const override;

 private:
  SourceConfig config_;
  FunctionalReplayer& replayer_;
  RayFeed feed_;
  TraceRay tr_;
  EmittedRay er_;
  uint64_t index_ = 0;
  SourceCounters counters_;
};

}  // namespace vbsim::hw
