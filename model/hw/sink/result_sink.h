// Part contract (hw/sink/): where finished rays leave: the conclusion of each
// ray (verdict, statistics), the user's callback, the latencies, and lines put
// back in trace order (hw/sink/trace_order_buffer.h). Called by the scheduler
// (hw/scheduler/) once per finished ray; it calls the datapath's conclusion and
// the user's callback, nothing of the hardware.
//
// ResultSink: where finished rays leave the accelerator. It runs the datapath's
// conclusion of the ray (FunctionalReplayer::conclude: the method's answer, the
// verdict against the trace's exact answer, the per-kind statistics), hands the
// outcome to the user's callback (the hits file, a test) and keeps the per-ray
// latency (dispatch to result) and its histogram.
//
// Replaced (AcceleratorUnits::result_sink): the replacement, bound to the
// port `forward`, receives every finished ray in place of the conclusion and
// the callback (the run's verdicts and per-kind statistics are then its own
// business); this module stays, as `result_accounting`, for the run's
// accounting (rays finished, last cycle, latencies), which the accelerator's
// completion and statistics read.
#pragma once
#include <cstdint>

#include <systemc>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/observe/stat_provider.h"
#include "hw/source/ray_feed.h"
#include "hw/unit_interfaces.h"

namespace vbsim::hw {

class ResultSink final : public sc_core::sc_module, public ResultSinkIf, public StatProvider {
 public:
  sc_core::sc_export<ResultSinkIf> target;
  /// A replacement sink, when bound: receives every ray in place of the conclusion.
  sc_core::sc_port<ResultSinkIf, 1, sc_core::SC_ZERO_OR_MORE_BOUND> forward;

  /// `replayer` outlives the sink.
  ResultSink(sc_core::sc_module_name name, const HwConfig& config, FunctionalReplayer& replayer);
  void set_callback(RayResultSink callback) { callback_ = std::move(callback); }
  /// A closed-loop shader (replay/closed_loop.h) that receives every outcome
  /// after the callback; null: none. Not called when a replacement is bound.
  void set_shader(RayShader* shader) { shader_ = shader; }

  void ray_done(const TraceRay& tr, const EmittedRay& er, const Hit& hit, uint64_t rejected, uint64_t dispatched,
                uint64_t now, uint64_t trace_index) final;

  const SinkCounters& counters() const { return counters_; }
  const char* unit_kind() const override { return "ResultSink"; }
  nlohmann::json parameters() const override;

 private:
  void start_of_simulation() override;

  FunctionalReplayer& replayer_;
  ResultSinkIf* forward_if_ = nullptr;  // forward's interface, once bound
  RayResultSink callback_;
  RayShader* shader_ = nullptr;
  uint32_t bucket_cycles_;
  SinkCounters counters_;
};

}  // namespace vbsim::hw
