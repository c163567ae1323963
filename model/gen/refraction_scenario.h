// The `refraction` scenario: closed glass objects (a UV sphere of radius 1 and
// a cube of side 2, outward winding) with camera rays that enter them and
// bounce inside. At every hit the renderer emits the mirror reflection (a
// leaf) and follows the transmitted ray: the refraction into or out of the
// glass, or the total-internal-reflection child (kind reflect) when there is
// none. Sign bits matter here: an entering refraction (sign 1) meets the far
// wall from behind (bit 0), a TIR child inside (sign 1) meets another wall from
// behind too, so the validity bit must never treat those exit hits as suspects.
// Settings: objects (sphere,box), ior (1.5), bounces (transmitted rays followed
// per path, 4), segments (sphere, 32), hitpoint (ray, barycentric, both).
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_refraction_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
