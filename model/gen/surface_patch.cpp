#include "gen/surface_patch.h"

#include <cmath>

namespace vbsim {

SurfaceFrame tilted_frame(DVec3 centre, double tilt) {
  const DVec3 axis = dunit({1, 1, 0});
  // Rodrigues rotation of +z about `axis` by `tilt`; axis is perpendicular to z.
  const DVec3 z{0, 0, 1};
  const DVec3 n = std::cos(tilt) * z + std::sin(tilt) * dcross(axis, z);
  SurfaceFrame f;
  f.centre = centre;
  f.n = dunit(n);
  f.e1 = dunit(dcross(axis, f.n));
  f.e2 = dcross(f.n, f.e1);
  return f;
}

std::vector<Triangle> tessellate(const std::function<DVec3(double, double)>& map, double a0, double a1,
                                 int na, double b0, double b1, int nb) {
  std::vector<Vec3f> grid;
  for (int j = 0; j <= nb; ++j)
    for (int i = 0; i <= na; ++i)
      grid.push_back(to_vec3f(map(a0 + (a1 - a0) * i / na, b0 + (b1 - b0) * j / nb)));
  const auto at = [&](int i, int j) { return grid[static_cast<size_t>(j * (na + 1) + i)]; };
  std::vector<Triangle> tris;
  for (int j = 0; j < nb; ++j)
    for (int i = 0; i < na; ++i) {
      tris.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      tris.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return tris;
}

DVec3 folded_sheet(const SurfaceFrame& f, double fold, double a, double b) {
  if (a <= 0) return f.at(a, b, 0);
  return f.centre + a * (std::cos(fold) * f.e1 + std::sin(fold) * f.n) + b * f.e2;
}

}  // namespace vbsim
