// The `terminator` scenario: the shadow terminator of low-poly meshes with
// interpolated vertex normals (the shading-position gist). One case per
// tessellation: a UV sphere of radius 1 with `segments` steps of longitude and
// segments/2 rings, vertex normals the true sphere normals, lit by a distant
// point light (1000 radii away, nearly directional). Each camera ray is aimed
// at a random point of the sphere along its shading normal; its hit spawns one
// shadow ray toward the light (d = L - o, tmax 1) with parent_uv, parent_ns and
// the scene's vertex normals, so that the shading-position methods apply.
// Points come from two populations, both with the shading normal facing the light:
//   band: the geometric normal faces away (the gist's problem: the flat mesh
//         really shadows the point, so the exact answer is "occluded");
//   lit:  the geometric normal faces the light too (exactly visible; an origin
//         rounded below its own triangle re-hits it: shadow acne).
// Settings: segments (list, 8,16,32,64), band (fraction of band points, 0.5),
// hitpoint (ray, barycentric or both: alternate, the default).
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_terminator_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
