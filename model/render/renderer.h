// Renderer of `vbsim render`: a small image of a scene in which every ray goes
// through the replay datapath (the same emission, tester, self-intersection
// method and verdicts as `vbsim replay`) and is also answered by the exact
// oracle, so each pixel knows whether the method got its shadow and bounce
// rays right. The rays come from a closed-loop shader (render/render_shader.h):
// each child is made from its parent's answer, so a method's errors change the
// rays that follow. render_scene runs it untimed; render/cycle_render.h runs
// the same shader on the cycle-level model, with the same image.
//
// Integrators (docs/render.md):
// - mirror (default): per pixel one primary ray; at its hit a shadow ray (when
//   the light is on the side the shading normal faces) and one mirror bounce
//   (about the shading normal); at the bounce's hit, its own shadow ray.
//   Colour: albedo * (ambient + (1 - ambient) * lambert * visible), mixed with
//   the bounce's colour (background when it escapes) by kMirrorWeight.
// - path: a diffuse path tracer, `samples` jittered paths a pixel, each with a
//   shadow ray at every hit (next-event estimation) and up to `max_bounces`
//   cosine-sampled bounces; the random numbers are a hash of (seed, pixel,
//   sample, bounce), so the image does not depend on the order rays finish.
// - ao: ambient occlusion, one camera ray a pixel through its centre and, at
//   its hit, `samples` occlusion queries (kind shadow, any hit) in
//   cosine-distributed directions about the shading normal, each `ao_radius`
//   times the scene's bounding-box diagonal long (d of that length, tmax 1).
//   Colour: albedo * the fraction of them unoccluded; background on a miss.
// - glass: every surface a smooth dielectric of index kGlassIor in air, one
//   camera ray a pixel through its centre and one child at each hit: the
//   refraction (kind refract; entering where the ray meets the front side,
//   dot(d, Ng) < 0), or the mirror reflection (kind reflect) on total internal
//   reflection, up to `max_bounces` of them. Colour: the background the path
//   escapes to times the product of its Fresnel transmittances (Schlick);
//   black when it is still inside after max_bounces.
// Child rays start at the barycentric hit point (u, v of the method's hit) and
// carry parent_t, parent_uv and parent_ns, exactly as a trace's child rays do.
// With children_from_exact, the exact answer decides instead (the reference
// renderer): its triangle, its t rounded to float32 and the barycentrics of
// o + t d on that triangle.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/render_light.h"
#include "replay/replay_options.h"
#include "replay/replay_stats.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/trace_record.h"

namespace vbsim {

enum class RenderIntegrator { Mirror, Path, Ao, Glass };
const char* render_integrator_name(RenderIntegrator i);  ///< "mirror", "path", "ao", "glass"

/// The glass integrator's index of refraction (air outside: 1).
constexpr float kGlassIor = 1.5f;
bool parse_render_integrator(const std::string& s, RenderIntegrator& out);

/// Largest samples per pixel and bounces a path takes.
constexpr int kMaxRenderSamples = 4096;
constexpr int kMaxRenderBounces = 16;

struct RenderSettings {
  int width = 160;
  int height = 120;
  CameraSpec camera;
  RenderLight light;
  RenderIntegrator integrator = RenderIntegrator::Mirror;
  int samples = 1;      ///< paths a pixel (path: 1..kMaxRenderSamples; mirror: 1); ao: occlusion rays a hit
  /// ao: an occlusion ray's length, times the scene's bounding-box diagonal (> 0, finite).
  float ao_radius = 0.1f;
  int max_bounces = 2;  ///< path: diffuse bounces a path takes at most; glass: refractions and reflections (0..kMaxRenderBounces)
  uint64_t seed = 1;    ///< of the path tracer's random numbers
  /// Children (and shadow visibility) from the exact oracle's answers instead
  /// of the method's: the reference renderer, whose rays do not depend on the
  /// method; the method still answers (and is scored on) every ray.
  bool children_from_exact = false;
};

/// Throws std::invalid_argument naming the setting that is out of range.
void check_render_settings(const RenderSettings& settings);

/// Per-pixel error marks (bit flags).
enum PixelMark : uint8_t {
  kMarkAcne = 1,  ///< some shadow or bounce ray of the pixel got a self_hit verdict
  kMarkLeak = 2,  ///< some shadow or bounce ray got missed or false_hit
};

struct RenderResult {
  int width = 0, height = 0;
  std::vector<uint8_t> image;          ///< shaded image, RGB8, row-major, top row first
  std::vector<uint8_t> errors;         ///< error image, RGB8 (legend: render_colours.h)
  std::vector<uint8_t> marks;          ///< PixelMark bits per pixel
  std::vector<int32_t> primary_prim;   ///< triangle the primary ray hit, or -1
  uint64_t acne_pixels = 0;            ///< pixels with kMarkAcne (also counted when leaking too)
  uint64_t leak_pixels = 0;            ///< pixels with kMarkLeak
  uint64_t unscored_rays = 0;          ///< rays the verdict could not score (inconsistent oracle)
  ReplayStats stats;                   ///< every ray, verdicts per ray kind, wall_s of the render
};

/// Renders `scene` with the method, tester and hit-point mode of `options`,
/// untimed. Throws std::invalid_argument on a bad size, camera or setting.
/// `on_cast` (may be empty) receives every ray as it is cast, its `expect`
/// filled (a closed-loop trace); `on_pixel` (may be empty) the number of
/// pixels finished so far, each time one is finished.
RenderResult render_scene(const Scene& scene, const Bvh& bvh, const ReplayOptions& options,
                          const RenderSettings& settings,
                          const std::function<void(const TraceRay&)>& on_cast = {},
                          const std::function<void(uint64_t)>& on_pixel = {});

}  // namespace vbsim
