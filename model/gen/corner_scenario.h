// The `corner` scenario: the inside corner of a box, where a tmin or an offset
// along the ray skips the adjacent wall (Ray Tracing Gems ch. 6, Figure 6-6):
// a child spawned a tiny distance from a wall and heading into it meets it
// nearer than the method's epsilon.
//
// Three walls of side `size` (`grid` x `grid` cells each) meet at a corner at
// `distance` from the origin, tilted; they face into the box. Per --rays
// camera ray, from inside the box: the target lies on a random wall at a gap
// 10^U[log10 gap_min, log10 gap_max] (scene units) from a random adjacent wall
// (and, one time in three, at such a gap from the third wall too: next to the
// corner vertex); from the hit, `children` `diffuse` children head into the
// adjacent wall at elevations of 5 to 80 degrees from the spawn wall, and one
// `shadow` ray goes to a light behind the adjacent wall (tmax 1), which the
// wall must occlude. Setting hitpoint (barycentric).
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_corner_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
