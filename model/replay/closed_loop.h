// A closed-loop workload: rays made from the answers of the rays before them,
// as a renderer's shader makes them. The same shader runs untimed
// (run_functional_closed_loop, below) and on the cycle-level model
// (hw::Accelerator::set_shader, hw::run_cycle_closed_loop), and a user's own
// sc_main can hand one to the accelerator.
//
// Contract. next_ray() is asked for rays whenever the hardware can take one;
// it answers
//   Ray:      `out` is the next ray (ids unique, a child after its parent and
//             carrying the parent's hit as a trace ray does),
//   Later:    no ray now, more once a result it waits for has arrived (it is
//             asked again after the next on_result()),
//   Finished: no ray ever again (asked again, it answers Finished).
// on_result() receives every ray's answer (the hardware's: triangle, t,
// barycentrics, verdict and rejected candidates, RayOutcome) when it leaves
// the result sink, at `cycle` (0 untimed); children it makes there may be
// handed out at once: the ray source makes them ready shader.latency_cycles
// after their parent's result, as it does for a trace's children.
#pragma once
#include <cstdint>

#include "replay/functional_replayer.h"
#include "trace/trace_record.h"

namespace vbsim {

enum class ShaderAnswer : uint8_t { Ray, Later, Finished };

class RayShader {
 public:
  virtual ~RayShader() = default;
  /// The next ray to cast at `cycle` (see the contract above).
  virtual ShaderAnswer next_ray(TraceRay& out, uint64_t cycle) = 0;
  /// The answer to `ray`, as the result sink delivers it.
  virtual void on_result(const TraceRay& ray, const RayOutcome& outcome, uint64_t cycle) = 0;
};

/// Runs `shader` untimed: each ray it hands out is replayed at once and its
/// outcome returned before the next is asked for. Returns the rays cast.
/// Throws std::logic_error when the shader answers Later with no ray of its
/// outstanding (it would wait for ever).
uint64_t run_functional_closed_loop(RayShader& shader, FunctionalReplayer& replayer);

}  // namespace vbsim
