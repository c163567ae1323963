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

/// Renders `scene` on the accelerator configured by `cfg` (checked as
/// run_cycle_replay checks it). `on_cast` (may be empty) receives every ray
/// as it is cast. Throws std::invalid_argument on a bad setting, and what
/// run_cycle_replay throws; a run stopped by options.stop throws
/// std::runtime_error (a frame is never left half drawn).
CycleRenderResult render_scene_cycle(const Scene& scene, const Bvh& bvh, const ReplayOptions& options,
                                     const RenderSettings& settings, const hw::HwConfig& cfg,
                                     const hw::CycleRunOptions& run_options,
                                     const std::function<void(const TraceRay&)>& on_cast = {});

}  // namespace vbsim
