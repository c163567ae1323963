#include "gen/corner_scenario.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "gen/scenario_trace_builder.h"
#include "gen/seeded_random.h"
#include "gen/surface_patch.h"

namespace vbsim {

namespace {

/// The box's local axes: 0 = e1, 1 = e2, 2 = n of the frame; wall k is the
/// plane where local coordinate k is 0, facing +axis k (into the box).
DVec3 local_point(const SurfaceFrame& f, const double c[3]) { return f.at(c[0], c[1], c[2]); }
DVec3 axis_of(const SurfaceFrame& f, int k) { return k == 0 ? f.e1 : k == 1 ? f.e2 : f.n; }

std::vector<Triangle> corner_walls(const SurfaceFrame& f, double size, int grid) {
  std::vector<Triangle> tris;
  for (int k = 0; k < 3; ++k) {
    // Wall k spanned by axes k+1 and k+2 (cyclic): their cross product is axis k.
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const auto map = [&f, i, j](double x, double y) {
      double c[3] = {0, 0, 0};
      c[i] = x;
      c[j] = y;
      return local_point(f, c);
    };
    const std::vector<Triangle> wall = tessellate(map, 0, size, grid, 0, size, grid);
    tris.insert(tris.end(), wall.begin(), wall.end());
  }
  return tris;
}

}  // namespace

std::vector<ScenarioCase> generate_corner_scenario(const ScenarioSettings& s) {
  const double size = s.number("size", 2);
  const double distance = s.number("distance", 5);
  const int grid = static_cast<int>(s.integer("grid", 4));
  const double gap_min = s.number("gap_min", 1e-7);
  const double gap_max = s.number("gap_max", 1e-3);
  const int64_t children = s.integer("children", 4);
  const HitPointRule rule = read_hit_point_rule(s, HitPointRule::Barycentric);
  require_setting_range("size", size, 1e-30, 1e30);
  require_setting_range("distance", distance, 0, 1e30);
  require_setting_range("grid", grid, 1, 1000);
  require_setting_range("gap_min", gap_min, 1e-30, size / 10);
  require_setting_range("gap_max", gap_max, gap_min, size / 10);
  require_setting_range("children", static_cast<double>(children), 0, 10000);

  SeededRandom rng(s.seed());
  const SurfaceFrame f = tilted_frame(distance * dunit({-0.5, 0.9, 0.4}), 0.6);
  ScenarioTraceBuilder b(corner_walls(f, size, grid), rule);
  const auto gap = [&] { return std::pow(10.0, rng.uniform(std::log10(gap_min), std::log10(gap_max))); };
  for (int64_t r = 0; r < s.rays(); ++r) {
    const int k = static_cast<int>(rng.below(3));                   // spawn wall
    const int m = (k + 1 + static_cast<int>(rng.below(2))) % 3;      // adjacent wall to head into
    const int third = 3 - k - m;
    double c[3];
    c[k] = 0;
    c[m] = gap();
    c[third] = rng.uniform() < 1.0 / 3 ? gap() : rng.uniform(0.1, 0.9) * size;
    const DVec3 target = local_point(f, c);
    const double cam[3] = {rng.uniform(0.3, 0.7) * size, rng.uniform(0.3, 0.7) * size, rng.uniform(0.3, 0.7) * size};
    const Vec3f o = to_vec3f(local_point(f, cam));
    const SpawnPoint sp = b.shoot(o, to_vec3f(target) - o);
    if (!sp.hit()) continue;
    const DVec3 ek = axis_of(f, k), em = axis_of(f, m), et = axis_of(f, third);
    for (int64_t i = 0; i < children; ++i) {
      const double elev = rng.uniform(5, 80) * M_PI / 180;
      const DVec3 d = -std::cos(elev) * em + std::sin(elev) * ek + rng.uniform(-0.5, 0.5) * et;
      b.child(sp, RayKind::Diffuse, to_vec3f(dunit(d)));
    }
    const DVec3 light = target - 0.5 * size * em + 0.5 * size * ek + rng.uniform(-0.2, 0.2) * size * et;
    b.child(sp, RayKind::Shadow, to_vec3f(light) - sp.p, 1.0f);
  }
  return {b.take_case(
      "corner", fmt::format("inside corner of a box (three walls of side {}, {}x{} cells each, at distance {}): "
                            "spawn points {} to {} from an adjacent wall, {} diffuse children into it and a "
                            "shadow ray to a light behind it; hit points by {}",
                            size, grid, grid, distance, gap_min, gap_max, children, hit_point_rule_name(rule)))};
}

}  // namespace vbsim
