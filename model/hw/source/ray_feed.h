// How a trace reaches the accelerator and how its results leave: the callbacks
// a user of the model (vbsim replay, a test, a user's own sc_main) provides.
#pragma once
#include <cstdint>
#include <functional>

#include "replay/closed_loop.h"
#include "replay/functional_replayer.h"
#include "trace/trace_record.h"

namespace vbsim::hw {

/// Gives the next trace ray; false at the end of the trace.
using RayFeed = std::function<bool(TraceRay&)>;
/// A closed-loop feed: the next ray at a cycle, none now (more after the next
/// result) or none ever (replay/closed_loop.h, RayShader::next_ray).
using ShaderFeed = std::function<ShaderAnswer(TraceRay&, uint64_t cycle)>;
/// The text of an error located at the ray the feed gave last ("trace.jsonl:
/// line 12: field 'id': ..."), for checks the model makes on a ray after the
/// reader has passed it; may be empty (the error then names the trace position).
using RayLocator = std::function<std::string(const std::string& field, const std::string& message)>;

/// When a finished ray was where: cycles from the trace to the result sink.
struct RayTimes {
  uint64_t trace_index = 0;
  int64_t id = 0, parent = -1;
  uint64_t ready = 0;     ///< ready for emission (its parent's result plus the shading latency, or entering the buffer)
  uint64_t emitted = 0;   ///< the source started emitting it
  uint64_t started = 0;   ///< dispatched to a slot
  uint64_t finished = 0;  ///< its result reached the result sink
  uint32_t core = 0, slot = 0;  ///< slot: its index within the core
  uint64_t entered = 0;   ///< read into the ray source's buffer (<= ready)
};
using RayTimesSink = std::function<void(const RayTimes&)>;

/// Receives every finished ray, in completion order (may be empty);
/// `trace_index` is the ray's position in the feed (0 for the first ray).
using RayResultSink =
    std::function<void(const TraceRay&, const RayOutcome&, uint64_t finish_cycle, uint64_t trace_index)>;

}  // namespace vbsim::hw
