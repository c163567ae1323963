// Renderer of `vbsim render`: a small image of a scene in which every ray goes
// through the replay datapath (FunctionalReplayer: the same emission, tester,
// self-intersection method and verdicts as `vbsim replay`) and is also
// answered by the exact oracle, so each pixel knows whether the method got its
// shadow and bounce rays right.
//
// Per pixel: one primary ray; at its hit, a shadow ray (when the light is on the
// side the shading normal faces) and one mirror bounce (about the shading
// normal); at the bounce's hit, its own shadow ray. Child rays start at the
// barycentric hit point (u, v of the method's hit) and carry parent_t,
// parent_uv and parent_ns, exactly as a trace's child rays do.
// Colour: albedo * (ambient + (1 - ambient) * lambert * visible), mixed with the
// bounce's colour (background when it escapes) by kMirrorWeight.
#pragma once
#include <cstdint>
#include <vector>

#include "render/camera.h"
#include "render/render_light.h"
#include "replay/replay_options.h"
#include "replay/replay_stats.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim {

struct RenderSettings {
  int width = 160;
  int height = 120;
  CameraSpec camera;
  RenderLight light;
};

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

/// Renders `scene` with the method, tester and hit-point mode of `options`.
/// Throws std::invalid_argument on a bad size or camera.
RenderResult render_scene(const Scene& scene, const Bvh& bvh, const ReplayOptions& options,
                          const RenderSettings& settings);

}  // namespace vbsim
