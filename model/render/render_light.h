// The light of `vbsim render`: a point light (a position; shadow rays d = L - p,
// tmax = 1, as the trace spec's shadow rays) or a directional light (the
// direction towards the light; shadow rays d = that direction, tmax infinite).
#pragma once
#include <string>

#include "datapath/vec3.h"

namespace vbsim {

struct RenderLight {
  enum class Kind { Point, Directional };
  Kind kind = Kind::Directional;
  Vec3f value{-0.6f, 1.0f, 0.4f};  ///< point: position; directional: towards the light
};

/// Parses "point:X,Y,Z" or "dir:X,Y,Z". Returns false with `error` saying what is wrong.
bool parse_render_light(const std::string& text, RenderLight& light, std::string& error);

/// "point:X,Y,Z" or "dir:X,Y,Z" (for messages and stats).
std::string render_light_name(const RenderLight& light);

}  // namespace vbsim
