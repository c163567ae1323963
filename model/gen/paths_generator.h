// Paths generator: multi-bounce light paths over a mesh, written as a renderer
// would hand them to the accelerator. At every hit the "renderer" computes the
// hit point (by the ray equation on even paths, by barycentrics on odd ones,
// the two ways Ray Tracing Gems ch. 6.2.1 compares) and emits a shadow ray to
// the light, a reflection (about the shading normal), a refraction (index of
// refraction `ior`; total internal reflection gives a `reflect` child) and a
// diffuse child; the path continues along one of the three, chosen at random.
// Child origins are the raw hit points, before any self-intersection offset.
// The generator finds where a path continues from that very origin (so that
// parent_t and parent_uv are what its tester found for the recorded ray), with
// primitive-ID exclusion and a tmin of 1e-6 of the scene's radius, as a renderer
// might. `expect` is left for the oracle.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/trace_record.h"

namespace vbsim {

/// How the "renderer" computes hit points: alternating per path (even paths by
/// the ray equation, odd ones by barycentrics), or always one way.
enum class PathsHitPoints { Alternate, RayEquation, Barycentric };

/// The `hitpoint` setting's value ("both", "ray", "barycentric"); throws
/// naming the setting otherwise.
PathsHitPoints paths_hit_point_mode(const std::string& text);

struct PathsParams {
  int paths = 200;        ///< camera rays
  int max_depth = 3;      ///< hits along one path at most
  uint64_t seed = 1;
  float ior = 1.5f;       ///< index of refraction of the mesh's material
  PathsHitPoints hit_points = PathsHitPoints::Alternate;
};

struct GeneratedPaths {
  Vec3f light;                  ///< point light above the scene
  std::vector<TraceRay> rays;   ///< in emission order: parents before children
};

GeneratedPaths generate_paths(const Scene& scene, const Bvh& bvh, const PathsParams& params);

}  // namespace vbsim
