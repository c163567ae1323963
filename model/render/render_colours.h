// Colours of `vbsim render`: the shaded image's constants and the error
// image's legend (docs/render.md). Shaded colours are linear in [0, 1] and
// written as round(255 c), no gamma.
#pragma once
#include <array>
#include <cstdint>

#include "datapath/vec3.h"

namespace vbsim {

using Rgb8 = std::array<uint8_t, 3>;

/// Pixels whose primary ray hits nothing, and mirror rays that escape.
constexpr Rgb8 kBackgroundRgb{60, 72, 96};
/// Diffuse reflectance of every surface.
constexpr Vec3f kAlbedo{0.80f, 0.72f, 0.60f};
/// Light that reaches a surface whatever the shadow ray says (fraction of full).
constexpr float kAmbient = 0.12f;
/// Share of the mirror bounce in a pixel's colour.
constexpr float kMirrorWeight = 0.25f;

/// Error image legend.
constexpr Rgb8 kAcneRgb{255, 40, 40};   ///< a self hit (shadow acne, self-reflection)
constexpr Rgb8 kLeakRgb{0, 170, 255};   ///< a miss or a false hit (light leak, skipped occluder)
constexpr Rgb8 kBothRgb{255, 215, 0};   ///< both in one pixel

/// The background as linear colour.
inline Vec3f background_linear() {
  return {kBackgroundRgb[0] / 255.0f, kBackgroundRgb[1] / 255.0f, kBackgroundRgb[2] / 255.0f};
}

/// round(255 c) per channel, clamped to [0, 255].
Rgb8 to_rgb8(Vec3f linear);

/// Grey level of a pixel for the error image: (77 r + 150 g + 29 b) / 256.
uint8_t grey_of(const Rgb8& c);

}  // namespace vbsim
