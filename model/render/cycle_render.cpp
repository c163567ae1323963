#include "render/cycle_render.h"

#include <stdexcept>

#include "render/render_shader.h"

namespace vbsim {

void check_closed_loop_config(const hw::HwConfig& cfg) {
  if (!cfg.source.dependencies)
    throw std::invalid_argument(
        "field 'hw.source.dependencies': false has no closed loop: a render makes each child from its parent's "
        "answer, so the child always waits for it, while a replay of the frame's --trace-out with dependencies off "
        "makes every ray ready at once and counts other cycles (for no shader time set shader.latency_cycles to 0; "
        "docs/render.md)");
}

CycleRenderResult render_scene_cycle(const Scene& scene, const Bvh& bvh, const ReplayOptions& options,
                                     const RenderSettings& settings, const hw::HwConfig& cfg,
                                     const hw::CycleRunOptions& run_options,
                                     const std::function<void(const TraceRay&)>& on_cast,
                                     const std::function<void(uint64_t)>& on_pixel) {
  check_closed_loop_config(cfg);
  RenderShader shader(scene, bvh, settings, options.parent_window);
  shader.set_cast_callback(on_cast);
  shader.set_pixel_callback(on_pixel);
  CycleRenderResult r;
  r.run = hw::run_cycle_closed_loop(shader, scene, bvh, options, cfg, {}, run_options);
  if (r.run.stats.partial) throw std::runtime_error("render stopped before its last ray: no image written");
  r.render = shader.take_result();
  r.render.stats = r.run.stats;
  return r;
}

}  // namespace vbsim
