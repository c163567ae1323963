#include "render/renderer.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "render/render_shader.h"
#include "replay/closed_loop.h"
#include "replay/functional_replayer.h"

namespace vbsim {

const char* render_integrator_name(RenderIntegrator i) {
  switch (i) {
    case RenderIntegrator::Path: return "path";
    case RenderIntegrator::Ao: return "ao";
    case RenderIntegrator::Glass: return "glass";
    default: return "mirror";
  }
}

bool parse_render_integrator(const std::string& s, RenderIntegrator& out) {
  for (const RenderIntegrator i :
       {RenderIntegrator::Mirror, RenderIntegrator::Path, RenderIntegrator::Ao, RenderIntegrator::Glass})
    if (s == render_integrator_name(i)) {
      out = i;
      return true;
    }
  return false;
}

void check_render_settings(const RenderSettings& s) {
  if (s.width < 1 || s.height < 1 || s.width > 8192 || s.height > 8192)
    throw std::invalid_argument(fmt::format("image size {}x{}: width and height must be 1 to 8192", s.width, s.height));
  if ((s.integrator == RenderIntegrator::Mirror || s.integrator == RenderIntegrator::Glass) && s.samples != 1)
    throw std::invalid_argument(fmt::format("samples {}: the {} integrator traces one camera ray a pixel (the path "
                                            "integrator takes more)",
                                            s.samples, render_integrator_name(s.integrator)));
  if (s.samples < 1 || s.samples > kMaxRenderSamples)
    throw std::invalid_argument(fmt::format("samples {}: must be 1 to {}", s.samples, kMaxRenderSamples));
  if (s.integrator == RenderIntegrator::Ao && !(s.ao_radius > 0.0f && std::isfinite(s.ao_radius)))
    throw std::invalid_argument(fmt::format("ao radius {}: must be a positive finite fraction of the scene's "
                                            "bounding-box diagonal", s.ao_radius));
  if (s.max_bounces < 0 || s.max_bounces > kMaxRenderBounces)
    throw std::invalid_argument(fmt::format("bounces {}: must be 0 to {}", s.max_bounces, kMaxRenderBounces));
}

RenderResult render_scene(const Scene& scene, const Bvh& bvh, const ReplayOptions& options,
                          const RenderSettings& settings, const std::function<void(const TraceRay&)>& on_cast,
                          const std::function<void(uint64_t)>& on_pixel) {
  RenderShader shader(scene, bvh, settings, options.parent_window);
  shader.set_cast_callback(on_cast);
  shader.set_pixel_callback(on_pixel);
  FunctionalReplayer replayer(scene, bvh, options);
  const auto start = std::chrono::steady_clock::now();
  run_functional_closed_loop(shader, replayer);
  RenderResult r = shader.take_result();
  r.stats = replayer.stats();
  r.stats.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace vbsim
