// The renderer on the cycle-level model: the same closed-loop shader as
// render_scene (render/render_shader.h), its rays cast by the accelerator's
// ray source and its answers taken from the result sink, so the image, its
// errors and the frame's cycles, latencies and energy come from one run.
// The image equals render_scene's for the same method (each ray's answer
// depends only on the ray); the rays' order, and so the cycles, are the
// hardware's.
#pragma once
#include <functional>

#include "hw/cycle_replay.h"
#include "render/renderer.h"

namespace vbsim {

struct CycleRenderResult {
  RenderResult render;     ///< image, error image, pixel counts; stats of mode "cycle"
  hw::CycleRunResult run;  ///< the `hw` section, its table and counters (run.stats: as render.stats)
};

/// Throws std::invalid_argument naming the field when `cfg` cannot run a
/// closed loop with the promise above, that its trace replays to its cycles:
/// `source.dependencies` false. In a closed loop a child is made from its
/// parent's answer, so it always waits for it (dependencies off would only
/// drop the shader's latency, which `shader.latency_cycles` 0 does), while a
/// replay of the frame's trace with dependencies off makes every ray ready at
/// once, children before their parents' answers, and counts other cycles.
void check_closed_loop_config(const hw::HwConfig& cfg);

/// Renders `scene` on the accelerator configured by `cfg` (checked as
/// run_cycle_replay checks it, and by check_closed_loop_config). `on_cast`
/// (may be empty) receives every ray as it is cast, `on_pixel` (may be empty)
/// the number of pixels finished so far, each time one is finished. Throws
/// std::invalid_argument on a bad setting, and what run_cycle_replay throws;
/// a run stopped by options.stop throws std::runtime_error (a frame is never
/// left half drawn).
CycleRenderResult render_scene_cycle(const Scene& scene, const Bvh& bvh, const ReplayOptions& options,
                                     const RenderSettings& settings, const hw::HwConfig& cfg,
                                     const hw::CycleRunOptions& run_options,
                                     const std::function<void(const TraceRay&)>& on_cast = {},
                                     const std::function<void(uint64_t)>& on_pixel = {});

}  // namespace vbsim
