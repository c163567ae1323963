// The `coplanar` scenario: duplicated and overlapping coplanar triangles in the
// plane z = `z`: triangle 0, an exact duplicate (1), a duplicate with reversed
// winding (2), the triangle sharing its diagonal (3), and an overlapping
// triangle with no shared vertex (4). Camera rays from above hit points of the
// unit square (exact ties between the stacked triangles: any of them is
// correct); each hit spawns a reflection, a diffuse child and a shadow ray up,
// which must not re-hit the stack (the intended origin lies in its plane).
// Every fifth camera ray lies in the plane itself: the spec says a triangle in
// a plane containing the ray is not hit. Settings: z (0.5), hitpoint.
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_coplanar_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
