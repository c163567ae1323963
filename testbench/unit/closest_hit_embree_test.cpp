// The datapath's closest-hit search (project BVH + each tester, method none)
// against Embree's rtcIntersect1 on random rays at the bundled bunny: every
// well-conditioned ray (its hit more than 1e-4 in barycentrics from any edge,
// in both answers) must return the same triangle, and t to a relative 1e-5
// (three-half-plane) or 1e-4 (Moller-Trumbore).
#include <catch2/catch.hpp>

#include <algorithm>

#include "bench/functional_bench.h"
#include "datapath/closest_hit.h"
#include "datapath/testers.h"
#include "scene/embree_reference.h"

using namespace vbsim;

namespace {

bool well_conditioned(float u, float v) {
  constexpr float margin = 1e-4f;
  return u > margin && v > margin && 1.0f - u - v > margin;
}

template <class Tester>
void check_against_embree(const char* name, double t_tolerance) {
  const Scene scene = load_scene(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj");
  const Bvh bvh = build_bvh(scene);
  const EmbreeReference embree(scene);
  const std::vector<TraceRay> rays = bench_rays(scene, 20000, 7);
  const CandidateFilter none{SelfIntersectionMethod{}};
  int compared = 0, hits = 0, misses = 0;
  for (const TraceRay& tr : rays) {
    Ray r;
    r.o = tr.o;
    r.d = tr.d;
    CandidateCounters cc;
    TraversalCounters tc;
    const Hit ours = closest_hit<Tester>(bvh, r, none, cc, tc);
    int32_t prim;
    float t, u, v;
    const bool theirs = embree.intersect(r.o, r.d, 0.0f, r.tmax, prim, t, u, v);
    if (!theirs && !ours.valid()) {
      ++misses;
      ++compared;
      continue;
    }
    if (theirs && !well_conditioned(u, v)) continue;
    if (ours.valid() && !well_conditioned(ours.u, ours.v)) continue;
    ++compared;
    INFO(name << " ray " << tr.id);
    REQUIRE(ours.valid() == theirs);
    CHECK(ours.prim == prim);
    CHECK(ours.t == Approx(t).epsilon(t_tolerance));
    ++hits;
  }
  // Most rays are compared, and both hits and misses are exercised.
  CHECK(compared > 19000);
  CHECK(hits > 5000);
  CHECK(misses > 1000);
}

}  // namespace

TEST_CASE("three-half-plane closest hits agree with Embree on the bunny", "[closest_hit][embree]") {
  check_against_embree<ThreeHalfPlaneTester>("three-half-plane", 1e-5);
}

TEST_CASE("Moller-Trumbore closest hits agree with Embree on the bunny", "[closest_hit][embree]") {
  // Float Moller-Trumbore computes t from a cancelling triple product: its t
  // drifts more on thin triangles (1.1e-5 relative seen on this seed).
  check_against_embree<MollerTrumboreTester>("moller-trumbore", 1e-4);
}

TEST_CASE("Embree's 4-wide tree answers as its default one, and a structure it lacks is an error", "[embree]") {
  const Scene scene = load_scene(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj");
  const EmbreeReference chosen(scene), four_wide(scene, "bvh4.triangle4v");
  const BenchWorkload rays = random_workload(scene, ReplayOptions{}, 4000, 3);
  std::vector<int32_t> a, b;
  time_embree(chosen, rays, a);
  time_embree(four_wide, rays, b);
  CHECK(a == b);
  CHECK(std::count(a.begin(), a.end(), -1) < 3000);  // the rays hit, too
  CHECK_THROWS_WITH(EmbreeReference(scene, "bvh4.nonesuch"),
                    Catch::Contains("unknown triangle acceleration structure bvh4.nonesuch"));
  CHECK_THROWS_WITH(EmbreeReference(scene, "bvh4.triangle4v,threads=2"), Catch::Contains("only letters, digits"));
}
