// The children a renderer spawns at a hit on a glass-like surface: the mirror
// reflection, the refraction (Snell, index `ior` inside the closed side that
// Ng points out of; on total internal reflection a second `reflect` child
// instead), and a shadow ray toward a point light. Directions are computed in
// double about the unit geometric normal and rounded once.
#pragma once
#include <vector>

#include "gen/renderer_hits.h"

namespace vbsim {

struct SurfaceChildren {
  TraceRay reflect;
  TraceRay transmit;  ///< kind refract, or reflect on total internal reflection
  bool total_internal = false;
};

/// Reflection and refraction children of `parent` at its hit `h`.
SurfaceChildren glass_children(const TraceRay& parent, const Hit& h, const Scene& scene, double ior,
                               RendererHitPoint rule);

}  // namespace vbsim
