// Filling a trace's `expect` fields with the oracle's exact answers.
#pragma once
#include <vector>

#include "exact/oracle.h"

namespace vbsim {

/// id -> (o, d) of every ray, the parents intended_ray looks up.
ParentRays collect_parent_rays(const std::vector<TraceRay>& rays);

/// Sets has_expect, expect_prim and (for hits) has_expect_t / expect_t, the exact
/// t rounded to nearest double, on every ray; misses get expect_prim = -1 and no t.
void fill_expect(std::vector<TraceRay>& rays, const Scene& scene, const Bvh& bvh);

}  // namespace vbsim
