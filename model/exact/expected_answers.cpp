#include "exact/expected_answers.h"

#include <algorithm>

namespace vbsim {

ParentRays collect_parent_rays(const std::vector<TraceRay>& rays) {
  ParentRays parents;
  parents.reserve(rays.size());
  for (const TraceRay& r : rays) parents.emplace(r.id, ParentRay{r.o, r.d});
  return parents;
}

OracleAnswer fill_expect(TraceRay& r, const Oracle& oracle, const Scene& scene, const ParentRay* parent) {
  OracleAnswer a = oracle.answer(intended_ray(r, scene, parent));
  r.has_expect = true;
  r.expect_prim = a.prim;
  r.has_expect_t = a.prim >= 0;
  r.expect_t = a.prim >= 0 ? a.t : 0.0;
  return a;
}

OracleAnswer ExpectationFiller::fill(TraceRay& r) {
  OracleAnswer a = fill_expect(r, oracle_, scene_, parents_.lookup(r.parent));
  parents_.add(r.id, r.o, r.d);
  return a;
}

void fill_expect(std::vector<TraceRay>& rays, const Scene& scene, const Bvh& bvh) {
  ExpectationFiller filler(scene, bvh, std::max<int64_t>(1, static_cast<int64_t>(rays.size())));
  for (TraceRay& r : rays) filler.fill(r);
}

}  // namespace vbsim
