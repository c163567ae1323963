#include "gen/grazing_scenario.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "gen/grazing_children.h"
#include "gen/scenario_trace_builder.h"
#include "gen/seeded_random.h"
#include "gen/surface_patch.h"

namespace vbsim {

namespace {

struct GrazingParams {
  double size, distance, radius, angle_min, angle_max;
  int grid;
  int64_t angles;
};

std::function<DVec3(double, double)> surface_map(const std::string& name, const SurfaceFrame& f, double r) {
  if (name == "plane") return [f](double a, double b) { return f.at(a, b, 0); };
  if (name == "cylinder")  // axis along e2, bulging toward +n
    return [f, r](double a, double b) { return f.at(r * std::sin(a / r), b, r * std::cos(a / r) - r); };
  if (name == "bowl")  // sphere cap seen from inside, centre at +r n
    return [f, r](double a, double b) { return f.at(a, b, r - std::sqrt(r * r - a * a - b * b)); };
  throw std::runtime_error(fmt::format("option '--set surfaces': unknown surface '{}' (plane, cylinder, bowl)", name));
}

ScenarioCase grazing_case(const std::string& surface, const GrazingParams& p, int64_t rays, HitPointRule rule,
                          SeededRandom& rng) {
  const SurfaceFrame f = tilted_frame(p.distance * dunit({1.0, 0.6, 0.3}), 0.5);
  const auto map = surface_map(surface, f, p.radius);
  const double h = p.size / 2;
  ScenarioTraceBuilder b(tessellate(map, -h, h, p.grid, -h, h, p.grid), rule);
  const std::vector<double> angles = log_spaced(p.angle_min, p.angle_max, p.angles);
  for (int64_t i = 0; i < rays; ++i) {
    const DVec3 target = map(rng.uniform(-0.8, 0.8) * h, rng.uniform(-0.8, 0.8) * h);
    const DVec3 camera = target + 2.0 * p.size * dunit(f.n + rng.uniform(-0.5, 0.5) * f.e1 +
                                                       rng.uniform(-0.5, 0.5) * f.e2);
    const Vec3f o = to_vec3f(camera);
    const SpawnPoint s = b.shoot(o, to_vec3f(target) - o);
    if (s.hit()) add_grazing_children(b, s, angles, rng);
  }
  return b.take_case(
      fmt::format("grazing-{}", surface),
      fmt::format("grazing children off a tessellated {} ({}x{} cells, side {}, at distance {} from the "
                  "origin, radius {}): {} elevation angles from {} to {} rad per hit; hit points by {}",
                  surface, p.grid, p.grid, p.size, p.distance, p.radius, p.angles, p.angle_min, p.angle_max,
                  hit_point_rule_name(rule)));
}

}  // namespace

std::vector<ScenarioCase> generate_grazing_scenario(const ScenarioSettings& s) {
  GrazingParams p{};
  const std::vector<std::string> surfaces = setting_list(s, "surfaces", "plane,cylinder,bowl");
  p.size = s.number("size", 2);
  p.distance = s.number("distance", 5);
  p.radius = s.number("radius", 10);
  p.grid = static_cast<int>(s.integer("grid", 16));
  p.angle_min = s.number("angle_min", 1e-6);
  p.angle_max = s.number("angle_max", 10 * M_PI / 180);
  p.angles = s.integer("angles", 8);
  const HitPointRule rule = read_hit_point_rule(s, HitPointRule::Barycentric);
  require_setting_range("size", p.size, 1e-30, 1e30);
  require_setting_range("distance", p.distance, 0, 1e30);
  require_setting_range("radius", p.radius, p.size, 1e30);
  require_setting_range("grid", p.grid, 1, 1000);
  require_setting_range("angle_min", p.angle_min, 1e-30, M_PI / 2);
  require_setting_range("angle_max", p.angle_max, p.angle_min, M_PI / 2);
  require_setting_range("angles", static_cast<double>(p.angles), 1, 10000);

  SeededRandom rng(s.seed());
  std::vector<ScenarioCase> cases;
  for (const std::string& surface : surfaces) cases.push_back(grazing_case(surface, p, s.rays(), rule, rng));
  return cases;
}

}  // namespace vbsim
