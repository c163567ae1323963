// RenderShader: the renderer of `vbsim render` as a closed-loop shader
// (replay/closed_loop.h). It hands out each pixel's primary rays in pixel
// order, and every child it makes from an answer before the next primary
// (children first, oldest first); each ray it casts gets the next id and the
// exact oracle's answer (`expect`) at the moment it is cast, so the rays cast
// form a trace that can be replayed and scored. A pixel's colour is written
// once its last ray has returned, from terms kept in fixed places, so the
// image does not depend on the order in which answers come back.
#pragma once
#include <cstdint>
#include <deque>
#include <functional>
#include <unordered_map>
#include <vector>

#include "exact/expected_answers.h"
#include "render/camera.h"
#include "render/renderer.h"
#include "replay/closed_loop.h"

namespace vbsim {

class RenderShader final : public RayShader {
 public:
  /// `scene` and `bvh` outlive the shader; `parent_window`: rays the oracle
  /// keeps as parents (a child is cast at most that many rays after its
  /// parent; ParentWindowError otherwise). Throws std::invalid_argument on a
  /// bad size, camera or setting.
  RenderShader(const Scene& scene, const Bvh& bvh, const RenderSettings& settings, int64_t parent_window);

  ShaderAnswer next_ray(TraceRay& out, uint64_t cycle) override;
  void on_result(const TraceRay& ray, const RayOutcome& outcome, uint64_t cycle) override;

  /// Receives every ray as it is cast (its id and `expect` set); may be empty.
  void set_cast_callback(std::function<void(const TraceRay&)> on_cast) { on_cast_ = std::move(on_cast); }
  /// Receives the number of pixels finished so far each time a pixel is
  /// finished (for a progress display); may be empty.
  void set_pixel_callback(std::function<void(uint64_t)> on_pixel) { on_pixel_ = std::move(on_pixel); }
  /// The image, error image and pixel counts (stats and wall_s are the
  /// driver's). Throws std::logic_error before every pixel is finished.
  RenderResult take_result();
  uint64_t rays_cast() const { return next_id_; }

 private:
  enum class Role : uint8_t { Primary, Shadow, Bounce, Occlusion };
  /// What a ray in flight is for.
  struct RayContext {
    uint32_t pixel = 0;
    uint32_t sample = 0;
    uint32_t depth = 0;   ///< hits before its origin (0: a primary ray, or a shadow ray from the primary hit)
    Role role = Role::Primary;
    Vec3f weight;         ///< shadow: the term it adds when unoccluded; bounce: the path's throughput
  };
  struct Pending {
    TraceRay ray;
    RayContext context;
  };
  /// A pixel with rays still to come back.
  struct PixelState {
    uint32_t pending = 0;  ///< its rays made and not answered
    uint32_t primaries = 0;  ///< primary rays made
    uint8_t marks = 0;
    bool bounced = false, bounce_hit = false;  ///< mirror: a bounce was cast, and it hit
    float lit[2] = {0.0f, 0.0f};               ///< mirror: lambert x visible at the primary and the bounce hit; ao: [0] the unoccluded fraction
    Vec3f escaped{0, 0, 0};                    ///< glass: the background its path escaped to, times its transmittance
    std::vector<Vec3f> terms;  ///< path: [sample][slot], slot d < slots-1: light at hit d, last: background
  };

  /// Makes the rays a hit spawns (`in` hit `h`, which is hit number `depth`).
  void shade_hit(const TraceRay& in, const Hit& h, const RayContext& at);
  /// ao: the occlusion rays from the primary hit `child` (its origin and parent fields set).
  void cast_occlusion(const TraceRay& child, Vec3f ns, const RayContext& at);
  /// glass: the refraction (or, past the critical angle, the reflection) of
  /// `dn` at hit `child` on a surface whose geometric normal is `ng` and whose
  /// shading normal, on the side the ray came from, is `ns`.
  void cast_glass(const TraceRay& child, Vec3f dn, Vec3f ng, Vec3f ns, const RayContext& at);
  void make_primary();
  void push_child(const TraceRay& ray, const RayContext& context);
  void finish_pixel(uint32_t pixel, PixelState& p);
  Vec3f& term(PixelState& p, uint32_t sample, uint32_t slot) { return p.terms[sample * slots_ + slot]; }

  const Scene& scene_;
  RenderSettings settings_;
  PinholeCamera camera_;
  ExpectationFiller filler_;
  uint32_t pixels_;
  uint32_t slots_;  ///< path: terms a sample keeps (max_bounces + 2)
  float ao_length_;  ///< ao: an occlusion ray's length (ao_radius times the bounding-box diagonal)
  uint32_t camera_rays_;  ///< camera rays a pixel: samples (path), else 1 (ao's samples are occlusion rays)
  uint32_t next_pixel_ = 0, next_sample_ = 0;
  int64_t next_id_ = 0;
  std::deque<Pending> children_;
  std::unordered_map<int64_t, RayContext> in_flight_;
  std::unordered_map<uint32_t, PixelState> pixels_live_;
  std::function<void(const TraceRay&)> on_cast_;
  std::function<void(uint64_t)> on_pixel_;
  RenderResult result_;
  uint32_t finished_ = 0;
};

}  // namespace vbsim
