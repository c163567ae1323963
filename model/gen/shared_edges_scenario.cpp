#include "gen/shared_edges_scenario.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "gen/grazing_children.h"
#include "gen/scenario_trace_builder.h"
#include "gen/seeded_random.h"
#include "gen/surface_patch.h"

namespace vbsim {

namespace {

struct SharedEdgesParams {
  double size, distance, delta, angle_min, angle_max;
  int grid;
  int64_t ulps, angles;
};

double fold_of(const std::string& shape, double delta_rad) {
  if (shape == "flat") return 0.0;
  if (shape == "convex") return -delta_rad;
  if (shape == "concave") return delta_rad;
  throw std::runtime_error(fmt::format("option '--set shapes': unknown shape '{}' (flat, convex, concave)", shape));
}

float moved_by_ulps(float x, int64_t steps) {
  const float toward = steps < 0 ? -INFINITY : INFINITY;
  for (int64_t i = 0; i < std::abs(steps); ++i) x = std::nextafter(x, toward);
  return x;
}

ScenarioCase shared_edges_case(const std::string& shape, const SharedEdgesParams& p, int64_t rays,
                               HitPointRule rule, SeededRandom& rng) {
  const SurfaceFrame f = tilted_frame(p.distance * dunit({0.3, 1.0, 0.6}), 0.4);
  const double fold = fold_of(shape, p.delta * M_PI / 180);
  const double h = p.size / 2, cell = p.size / p.grid;
  const auto map = [&f, fold](double a, double b) { return folded_sheet(f, fold, a, b); };
  ScenarioTraceBuilder b(tessellate(map, -h, h, p.grid, -h, h, p.grid), rule);
  const std::vector<double> angles = log_spaced(p.angle_min, p.angle_max, p.angles);
  for (int64_t r = 0; r < rays; ++r) {
    // An interior vertex (i, j) of the grid; on the fold line (i = grid/2) half of the time.
    const int i = rng.uniform() < 0.5 ? p.grid / 2 : 1 + static_cast<int>(rng.below(p.grid - 1));
    const int j = 1 + static_cast<int>(rng.below(p.grid - 1));
    const Vec3f corner = to_vec3f(map(-h + i * cell, -h + j * cell));
    Vec3f target = corner;
    const uint64_t pick = rng.below(3);
    if (rng.uniform() >= 1.0 / 3) {  // a point of the edge along a, along b or the cell's diagonal
      const int di = pick == 1 ? 0 : 1, dj = pick == 0 ? 0 : 1;
      const DVec3 other = to_dvec(to_vec3f(map(-h + (i + di) * cell, -h + (j + dj) * cell)));
      const double s = rng.uniform();
      target = to_vec3f((1 - s) * to_dvec(corner) + s * other);
    }
    for (int c = 0; c < 3; ++c)
      target[c] = moved_by_ulps(target[c], static_cast<int64_t>(rng.below(2 * p.ulps + 1)) - p.ulps);
    const DVec3 camera = to_dvec(target) + p.size * dunit(f.n + rng.uniform(-0.4, 0.4) * f.e1 +
                                                           rng.uniform(-0.4, 0.4) * f.e2);
    const Vec3f o = to_vec3f(camera);
    const SpawnPoint s = b.shoot(o, target - o);
    if (s.hit()) add_grazing_children(b, s, angles, rng);
  }
  return b.take_case(
      fmt::format("shared-edges-{}", shape),
      fmt::format("{} sheet (dihedral 180{}{} degrees) of {}x{} cells, side {}, at distance {}: spawn points "
                  "within {} ulps of shared edges and vertices, {} grazing children from {} to {} rad; hit "
                  "points by {}",
                  shape, fold > 0 ? "-" : "+", std::fabs(fold) * 180 / M_PI, p.grid, p.grid, p.size, p.distance,
                  p.ulps, p.angles, p.angle_min, p.angle_max, hit_point_rule_name(rule)));
}

}  // namespace

std::vector<ScenarioCase> generate_shared_edges_scenario(const ScenarioSettings& s) {
  SharedEdgesParams p{};
  const std::vector<std::string> shapes = setting_list(s, "shapes", "flat,convex,concave");
  p.size = s.number("size", 2);
  p.distance = s.number("distance", 5);
  p.delta = s.number("delta", 0.5);
  p.grid = static_cast<int>(s.integer("grid", 8));
  p.ulps = s.integer("ulps", 4);
  p.angle_min = s.number("angle_min", 1e-6);
  p.angle_max = s.number("angle_max", 1 * M_PI / 180);
  p.angles = s.integer("angles", 6);
  const HitPointRule rule = read_hit_point_rule(s, HitPointRule::Barycentric);
  require_setting_range("size", p.size, 1e-30, 1e30);
  require_setting_range("distance", p.distance, 0, 1e30);
  require_setting_range("delta", p.delta, 0, 90);
  require_setting_range("grid", p.grid, 2, 1000);
  if (p.grid % 2) throw std::runtime_error(fmt::format("option '--set grid={}': must be even", p.grid));
  require_setting_range("ulps", static_cast<double>(p.ulps), 0, 1 << 20);
  require_setting_range("angle_min", p.angle_min, 1e-30, M_PI / 2);
  require_setting_range("angle_max", p.angle_max, p.angle_min, M_PI / 2);
  require_setting_range("angles", static_cast<double>(p.angles), 1, 10000);

  SeededRandom rng(s.seed());
  std::vector<ScenarioCase> cases;
  for (const std::string& shape : shapes) cases.push_back(shared_edges_case(shape, p, s.rays(), rule, rng));
  return cases;
}

}  // namespace vbsim
