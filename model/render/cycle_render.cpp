#include "render/cycle_render.h"

#include <stdexcept>

#include "render/render_shader.h"

namespace vbsim {

CycleRenderResult render_scene_cycle(const Scene& scene, const Bvh& bvh, const ReplayOptions& options,
                                     const RenderSettings& settings, const hw::HwConfig& cfg,
                                     const hw::CycleRunOptions& run_options,
                                     const std::function<void(const TraceRay&)>& on_cast) {
  RenderShader shader(scene, bvh, settings, options.parent_window);
  shader.set_cast_callback(on_cast);
  CycleRenderResult r;
  r.run = hw::run_cycle_closed_loop(shader, scene, bvh, options, cfg, {}, run_options);
  if (r.run.stats.partial) throw std::runtime_error("render stopped before its last ray: no image written");
  r.render = shader.take_result();
  r.render.stats = r.run.stats;
  return r;
}

}  // namespace vbsim
