#include "gen/grazing_children.h"

#include <cmath>

namespace vbsim {

DVec3 facing_normal(const ScenarioTraceBuilder& b, const SpawnPoint& s) {
  const DVec3 n = unit_normal(b.scene().triangles[s.prim]);
  return ddot(n, to_dvec(s.incoming)) > 0 ? -1.0 * n : n;
}

void add_grazing_children(ScenarioTraceBuilder& b, const SpawnPoint& s, const std::vector<double>& angles,
                          SeededRandom& rng) {
  const DVec3 n = facing_normal(b, s);
  const DVec3 t1 = any_perpendicular(n), t2 = dcross(n, t1);
  for (double angle : angles) {
    const double phi = rng.uniform(0, 2 * M_PI);
    const DVec3 tangent = std::cos(phi) * t1 + std::sin(phi) * t2;
    b.child(s, RayKind::Diffuse, to_vec3f(std::cos(angle) * tangent + std::sin(angle) * n));
  }
}

}  // namespace vbsim
