// The `crevice` scenario: concave wedges (Ray Tracing Gems ch. 6, Figure 6-8)
// where no offset is safe: near the crease, an offset along the wall's normal
// (fixed or adaptive) can carry the origin past the opposite wall, and a tmin
// skips that wall, so children that should hit it leak through.
//
// One case per opening angle (`angles`, a comma list in degrees, 1 to 90 by
// default 1,5,20,90): a sheet of side `size` folded to that opening angle
// about its middle line (2 `grid` x `grid` cells), tilted, at `distance` from
// the origin; both walls face into the wedge. Per --rays camera ray, from a
// point on the wedge's bisector, aimed at a point of one wall at a distance
// 10^U[log10 gap_min, log10 gap_max] (scene units) from the crease; from the
// hit, a mirror `reflect` child and `children` `diffuse` children
// (cosine-weighted about the wall's normal). Setting hitpoint (barycentric).
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_crevice_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
