// Grazing children of a spawn point, shared by the grazing and shared-edges
// scenarios: one `diffuse` child per elevation angle (radians, measured from
// the hit facet's plane toward the side the camera ray came from), each in a
// random azimuth about the facet's normal.
#pragma once
#include <vector>

#include "gen/scenario_trace_builder.h"
#include "gen/seeded_random.h"

namespace vbsim {

/// The hit facet's unit normal (double) on the side the camera ray came from.
DVec3 facing_normal(const ScenarioTraceBuilder& b, const SpawnPoint& s);

void add_grazing_children(ScenarioTraceBuilder& b, const SpawnPoint& s, const std::vector<double>& angles,
                          SeededRandom& rng);

}  // namespace vbsim
