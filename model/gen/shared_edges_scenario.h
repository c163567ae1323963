// The `shared-edges` scenario: spawn points within a few ulps of the shared
// edges and vertices of a tessellated sheet, children leaving at grazing
// angles, where primitive-ID exclusion fails (Ray Tracing Gems ch. 6, Figures
// 6-3 and 6-4): the child's false hit is on the neighbour, whose ID differs.
//
// One case per shape (`shapes`, a comma list of flat, convex, concave): a
// square sheet of side `size` with `grid` x `grid` cells (grid even), at
// `distance` from the origin, tilted, folded along its middle line so that
// the dihedral angle on the camera's side is 180 degrees (flat), 180 + `delta`
// (convex ridge) or 180 - `delta` (concave valley), delta in degrees. Per
// --rays camera ray: the target is a random interior grid vertex (one in
// three) or a random point of one of its three edges, on the fold line half
// of the time, moved by up to `ulps` float steps per coordinate; `angles`
// `diffuse` children leave the hit facet on the camera's side at elevations
// from `angle_min` to `angle_max` radians (log-spaced), in random azimuths.
// Setting hitpoint (barycentric).
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_shared_edges_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
