// Filling a trace's `expect` fields with the oracle's exact answers.
// Parents are looked up among the rays that came before, in trace order, the
// same way a replay finds them, so a trace's expectations and its verdicts use
// the same intended origins.
#pragma once
#include <vector>

#include "exact/oracle.h"

namespace vbsim {

/// id -> (o, d) of every ray, the parents intended_ray looks up.
ParentRays collect_parent_rays(const std::vector<TraceRay>& rays);

/// Sets expect on `ray` from the oracle's answer for it, its parent ray being
/// `parent` (null when it did not come before it): has_expect, expect_prim and
/// (for hits) has_expect_t / expect_t, the exact t rounded to nearest double;
/// a miss gets expect_prim = -1 and no t. Returns the answer.
OracleAnswer fill_expect(TraceRay& ray, const Oracle& oracle, const Scene& scene, const ParentRay* parent);

/// Streams a trace through the oracle, one ray at a time, in trace order,
/// keeping the last `parent_window` rays as parents (ParentRayStore).
class ExpectationFiller {
 public:
  ExpectationFiller(const Scene& scene, const Bvh& bvh,
                    int64_t parent_window = ParentRayStore::kDefaultWindow)
      : scene_(scene), oracle_(scene, bvh), parents_(parent_window) {}
  /// fill_expect with the ray's parent among the rays before it. Returns the
  /// answer; remembers the ray as a parent for later rays. Throws
  /// ParentWindowError when the ray's parent lies beyond the window.
  OracleAnswer fill(TraceRay& ray);

 private:
  const Scene& scene_;
  Oracle oracle_;
  ParentRayStore parents_;
};

/// ExpectationFiller over a whole vector of rays (every ray kept as a parent).
void fill_expect(std::vector<TraceRay>& rays, const Scene& scene, const Bvh& bvh);

}  // namespace vbsim
