// The `paths` scenario: multi-bounce camera paths over an existing mesh
// (paths_generator.h). Settings: scene (mesh file; the bundled bunny by
// default), depth (hits per path, 3), ior (1.5), hitpoint (both: ray equation on
// even paths, barycentrics on odd ones; ray; barycentric); --rays is the number of paths.
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_paths_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
