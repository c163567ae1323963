#include "gen/crevice_scenario.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "gen/grazing_children.h"
#include "gen/scenario_trace_builder.h"
#include "gen/seeded_random.h"
#include "gen/surface_patch.h"

namespace vbsim {

namespace {

struct CreviceParams {
  double size, distance, gap_min, gap_max;
  int grid;
  int64_t children;
};

double parse_angle(const std::string& item) {
  char* end = nullptr;
  const double a = std::strtod(item.c_str(), &end);
  if (*end != '\0' || !(a > 0 && a <= 180))
    throw std::runtime_error(fmt::format("option '--set angles': '{}' is not an angle in (0, 180] degrees", item));
  return a;
}

ScenarioCase crevice_case(const std::string& angle_text, const CreviceParams& p, int64_t rays, HitPointRule rule,
                          SeededRandom& rng) {
  const double opening = parse_angle(angle_text) * M_PI / 180;
  const double fold = M_PI - opening;
  const SurfaceFrame f = tilted_frame(p.distance * dunit({0.8, 0.2, 1.0}), 0.3);
  const double h = p.size / 2;
  const auto map = [&f, fold](double a, double b) { return folded_sheet(f, fold, a, b); };
  ScenarioTraceBuilder b(tessellate(map, -h, h, 2 * p.grid, -h, h, p.grid), rule);
  const DVec3 left = -1.0 * f.e1, right = std::cos(fold) * f.e1 + std::sin(fold) * f.n;
  const DVec3 bisector = dunit(left + right);
  for (int64_t r = 0; r < rays; ++r) {
    const double gap = std::pow(10.0, rng.uniform(std::log10(p.gap_min), std::log10(p.gap_max)));
    const double along = rng.uniform(-0.8, 0.8) * h;
    const bool on_left = rng.uniform() < 0.5;
    const DVec3 target = f.centre + along * f.e2 + gap * (on_left ? left : right);
    const DVec3 camera = f.centre + along * f.e2 + rng.uniform(0.3, 0.9) * h * bisector +
                         rng.uniform(-0.2, 0.2) * h * f.e2;
    const Vec3f o = to_vec3f(camera);
    const SpawnPoint s = b.shoot(o, to_vec3f(target) - o);
    if (!s.hit()) continue;
    const DVec3 n = facing_normal(b, s), d = dunit(to_dvec(s.incoming));
    b.child(s, RayKind::Reflect, to_vec3f(d - 2.0 * ddot(d, n) * n));
    for (int64_t k = 0; k < p.children; ++k)
      b.child(s, RayKind::Diffuse, to_vec3f(dunit(n + to_dvec(rng.unit_vector()))));
  }
  return b.take_case(
      fmt::format("crevice-{}deg", angle_text),
      fmt::format("concave wedge of opening angle {} degrees (side {}, {}x{} cells, at distance {}): spawn points "
                  "{} to {} from the crease, a reflect and {} diffuse children each; hit points by {}",
                  angle_text, p.size, 2 * p.grid, p.grid, p.distance, p.gap_min, p.gap_max, p.children,
                  hit_point_rule_name(rule)));
}

}  // namespace

std::vector<ScenarioCase> generate_crevice_scenario(const ScenarioSettings& s) {
  CreviceParams p{};
  const std::vector<std::string> angles = setting_list(s, "angles", "1,5,20,90");
  p.size = s.number("size", 2);
  p.distance = s.number("distance", 5);
  p.grid = static_cast<int>(s.integer("grid", 4));
  p.gap_min = s.number("gap_min", 1e-6);
  p.gap_max = s.number("gap_max", 1e-2);
  p.children = s.integer("children", 4);
  const HitPointRule rule = read_hit_point_rule(s, HitPointRule::Barycentric);
  require_setting_range("size", p.size, 1e-30, 1e30);
  require_setting_range("distance", p.distance, 0, 1e30);
  require_setting_range("grid", p.grid, 1, 1000);
  require_setting_range("gap_min", p.gap_min, 1e-30, p.size / 4);
  require_setting_range("gap_max", p.gap_max, p.gap_min, p.size / 4);
  require_setting_range("children", static_cast<double>(p.children), 0, 10000);

  SeededRandom rng(s.seed());
  std::vector<ScenarioCase> cases;
  for (const std::string& a : angles) cases.push_back(crevice_case(a, p, s.rays(), rule, rng));
  return cases;
}

}  // namespace vbsim
