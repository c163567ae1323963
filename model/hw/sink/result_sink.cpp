#include "hw/sink/result_sink.h"

#include <algorithm>

namespace vbsim::hw {

ResultSink::ResultSink(sc_core::sc_module_name name, const HwConfig& config, FunctionalReplayer& replayer)
    : sc_core::sc_module(name), target("target"), forward("forward"), replayer_(replayer), bucket_cycles_(config.latency_bucket_cycles) {
  target.bind(*this);
  counters_.latency_histogram.assign(config.latency_buckets, 0);
  declare_stat("rays", "rays", "rays finished", counters_.rays);
  declare_stat("last_cycle", "cycles", "cycle the last ray finished", counters_.last_cycle);
  declare_stat("latency_min", "cycles", "shortest dispatch-to-result latency", counters_.latency_min);
  declare_stat("latency_max", "cycles", "longest dispatch-to-result latency", counters_.latency_max);
  declare_stat("latency_mean", "cycles", "mean dispatch-to-result latency", [this] {
    return counters_.rays ? static_cast<double>(counters_.latency_sum) / static_cast<double>(counters_.rays) : 0.0;
  });
  declare_stat("latency_histogram", "rays", "rays per latency bucket (the last bucket open-ended)",
               [this] { return nlohmann::json(counters_.latency_histogram); });
}

void ResultSink::start_of_simulation() { forward_if_ = forward.size() ? forward[0] : nullptr; }

nlohmann::json ResultSink::parameters() const {
  return {{"latency_bucket_cycles", bucket_cycles_}, {"latency_buckets", counters_.latency_histogram.size()}};
}

void ResultSink::ray_done(const TraceRay& tr, const EmittedRay& er, const Hit& hit, uint64_t rejected,
                          uint64_t dispatched, uint64_t now, uint64_t trace_index) {
  if (forward_if_) {
    forward_if_->ray_done(tr, er, hit, rejected, dispatched, now, trace_index);
  } else {
    const RayOutcome out = replayer_.conclude(tr, er, hit, rejected);
    if (callback_) callback_(tr, out, now, trace_index);
    if (shader_) shader_->on_result(tr, out, now);  // its children reach the source (on_finish) next
  }
  SinkCounters& c = counters_;
  const uint64_t latency = now - dispatched;
  c.latency_sum += latency;
  c.latency_min = c.rays == 0 ? latency : std::min(c.latency_min, latency);
  c.latency_max = std::max(c.latency_max, latency);
  const uint64_t bucket = std::min<uint64_t>(latency / bucket_cycles_, c.latency_histogram.size() - 1);
  ++c.latency_histogram[bucket];
  c.latency_by_kind[static_cast<int>(tr.kind)].add(latency);
  ++c.rays;
  c.last_cycle = now;
}

}  // namespace vbsim::hw
