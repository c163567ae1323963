#include "exact/expected_answers.h"

namespace vbsim {

ParentRays collect_parent_rays(const std::vector<TraceRay>& rays) {
  ParentRays parents;
  parents.reserve(rays.size());
  for (const TraceRay& r : rays) parents.emplace(r.id, std::make_pair(r.o, r.d));
  return parents;
}

void fill_expect(std::vector<TraceRay>& rays, const Scene& scene, const Bvh& bvh) {
  const ParentRays parents = collect_parent_rays(rays);
  const Oracle oracle(scene, bvh);
  for (TraceRay& r : rays) {
    const OracleAnswer a = oracle.answer(intended_ray(r, scene, &parents));
    r.has_expect = true;
    r.expect_prim = a.prim;
    r.has_expect_t = a.prim >= 0;
    r.expect_t = a.prim >= 0 ? a.t : 0.0;
  }
}

}  // namespace vbsim
