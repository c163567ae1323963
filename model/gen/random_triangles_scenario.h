// The `random-triangles` scenario: isolated random triangles across a wide
// range of sizes and distances from the origin, one scene and trace per
// triangle so that no other geometry interferes (every hit a replay finds is
// then a re-intersection of the parent triangle). Two protocols (`protocol`):
//
// rtg (default): Ray Tracing Gems ch. 6, Figure 6-7. Centre at distance
//   2^U[dist_min_log2, dist_max_log2] from the origin in a uniform direction
//   (signed coordinates), vertices at 2^U[size_min_log2, size_max_log2] from
//   the centre in uniform directions; a fraction `straddle` of the triangles
//   has one centre coordinate set to 0, so the triangle straddles that
//   coordinate plane. A camera ray from a random point in front of the triangle
//   (at 1/4 to 16 times its size) hits a uniform random point; from the hit,
//   one mirror `reflect` child and children-1 `diffuse` children in uniform
//   sphere directions, tmax infinite.
// pbrt: pbrt-v4's `Triangle, Reintersect` law with random signs. Vertex coordinates
//   +-10^U[-exp, exp] (signs drawn, unlike pbrt); triangles with float |e1 x e2|^2 < 1e-20
//   are dropped and drawn again; a camera ray from a random point of the same
//   law aimed at a uniform random point of the triangle; from the hit,
//   `children` `diffuse` children in uniform sphere directions (tmax infinite)
//   and `targets` random target points of the same law, each reached by two
//   `shadow` rays d = target - p with tmax 1 and 1 - 1e-4 (pbrt's
//   SpawnRayTo(p2) uses 1 - ShadowEpsilon).
// --rays is the number of triangles; a camera ray that misses its triangle (a
// rare float miss) is drawn again. Setting of both: hitpoint (barycentric).
// pbrt-v4: pbrt-v4's own test as it runs it (gen/pbrt_reintersect.h): --rays
//   triangles RNG(first) .. RNG(first + rays - 1) (the index is pbrt's seed, so
//   --seed is not used), positive coordinates 10^U[-exp, exp], degenerate
//   triangles dropped and camera rays pbrt's test misses skipped (the case keeps
//   the camera ray, without children), both counted in every trace's
//   description; `children` SpawnRay and `children` SpawnRayTo rays per
//   triangle (pbrt: 1000; default 8), hit points as pbrt computes them.
#pragma once
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

std::vector<ScenarioCase> generate_random_triangles_scenario(const ScenarioSettings& settings);

}  // namespace vbsim
