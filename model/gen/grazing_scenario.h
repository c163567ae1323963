// The `grazing` scenario: children leaving a surface at grazing angles, where
// a tmin epsilon (and primitive-ID exclusion on a tessellated surface) fails:
// the child starts a rounding error off the surface, below it as often as
// above, and crosses it again at a distance of error / sin(angle), far beyond
// any tmin (Ray Tracing Gems ch. 6, Figures 6-4 and 6-5).
//
// One case per surface (`surfaces`, a comma list of plane, cylinder, bowl): a
// square patch of side `size` tessellated into `grid` x `grid` cells, centred
// at `distance` from the origin and tilted so that no coordinate plane is
// parallel to it; the cylinder (convex toward the camera) and the bowl
// (concave, a sphere cap) have radius `radius` (gently curved). Per --rays
// camera ray (aimed at a random point of the inner 80% of the patch), `angles`
// `diffuse` children leave the hit facet on the camera's side at elevation
// angles from `angle_min` to `angle_max` radians (log-spaced; 1e-6 to 10
// degrees by default) in random azimuths. Setting hitpoint (barycentric).
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_grazing_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
