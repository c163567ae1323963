// The `far-instance` scenario: a mesh placed far from the origin by a float32
// instance transform (the trace header's `transform`, a translation by 2^k
// along (1, 1, 1)), with multi-bounce paths over it (paths_generator.h). The
// generator loads the mesh through the same transform as a replay, so its rays
// and the oracle's expectations are on the scene exactly as replayed. One case
// per k. Fixed offsets and tmin fail once the coordinates' rounding exceeds
// them; Ray Tracing Gems ch. 6 says its adaptive offset scales with them.
// Settings: k (list, 20; each from 0 to 24), scene (the bundled bunny),
// depth (2), ior (1.5), hitpoint (ray, barycentric, both); --rays is the
// number of camera paths in all cases together.
#pragma once
#include <array>
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_far_instance_scenario(const ScenarioSettings& settings);

/// Row-major 4x4 translation by 2^k along (1, 1, 1).
std::array<float, 16> far_translation(int k);

}  // namespace vbsim
