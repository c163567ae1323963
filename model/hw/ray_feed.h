// How a trace reaches the accelerator and how its results leave: the callbacks
// a user of the model (vbsim replay, a test, a user's own sc_main) provides.
#pragma once
#include <cstdint>
#include <functional>

#include "replay/functional_replayer.h"
#include "trace/trace_record.h"

namespace vbsim::hw {

/// Gives the next trace ray; false at the end of the trace.
using RayFeed = std::function<bool(TraceRay&)>;
/// Receives every finished ray, in completion order (may be empty);
/// `trace_index` is the ray's position in the feed (0 for the first ray).
using RayResultSink =
    std::function<void(const TraceRay&, const RayOutcome&, uint64_t finish_cycle, uint64_t trace_index)>;

}  // namespace vbsim::hw
