// ResultSink: where finished rays leave the accelerator. It runs the datapath's
// conclusion of the ray (FunctionalReplayer::conclude: the method's answer, the
// verdict against the trace's exact answer, the per-kind statistics), hands the
// outcome to the user's callback (the hits file, a test) and keeps the per-ray
// latency (dispatch to result) and its histogram.
#pragma once
#include <cstdint>

#include <systemc>

#include "hw/hw_config.h"
#include "hw/hw_counters.h"
#include "hw/ray_feed.h"
#include "hw/stat_provider.h"
#include "hw/unit_interfaces.h"

namespace vbsim::hw {

class ResultSink final : public sc_core::sc_module, public ResultSinkIf, public StatProvider {
 public:
  sc_core::sc_export<ResultSinkIf> target;

  /// `replayer` outlives the sink.
  ResultSink(sc_core::sc_module_name name, const HwConfig& config, FunctionalReplayer& replayer);
  void set_callback(RayResultSink callback) { callback_ = std::move(callback); }

  void ray_done(const TraceRay& tr, const EmittedRay& er, const Hit& hit, uint64_t rejected, uint64_t dispatched,
                uint64_t now, uint64_t trace_index) final;

  const SinkCounters& counters() const { return counters_; }
  const char* unit_kind() const override { return "ResultSink"; }
  nlohmann::json parameters() const override;

 private:
  FunctionalReplayer& replayer_;
  RayResultSink callback_;
  uint32_t bucket_cycles_;
  SinkCounters counters_;
};

}  // namespace vbsim::hw
