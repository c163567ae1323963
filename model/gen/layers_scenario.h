// The `layers` scenario: surfaces closer together than a method's offset, so
// that an offset or tmin larger than the gap skips the neighbour (a missed hit:
// a light leak). Cases:
//   layers-sepS: two pairs of parallel squares near z = `z`, the upper one
//     `S * offset` above the lower one: on the left a pair facing the same way
//     (+z, a decal on a wall), on the right a thin sheet (upper +z, lower -z);
//   layers-nested-spheres: a UV sphere of radius 1 inside one of 1 + `shell`;
//   layers-sphere-on-plane: a UV sphere of radius 1 resting on a plane, hit
//     by grazing camera rays at points near the contact.
// Camera rays hit the upper (outer) surface; each hit spawns a refraction
// toward the neighbour, a reflection and a shadow ray toward a light on the
// far side of the neighbour (below the layers; at the spheres' centre; above
// the sphere on the plane), so that skipping the neighbour changes the answer.
// Settings: separation (list of multiples of the offset; 0.5,1.06,2.24,4.73,10
// log-spaced), offset (1e-4, the fixed offsets' default), z (1), shell (4e-5),
// segments (32), ior (1.5), hitpoint (ray, barycentric, both).
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_layers_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
