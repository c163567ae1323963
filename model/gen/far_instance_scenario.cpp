#include "gen/far_instance_scenario.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "gen/paths_generator.h"
#include "gen/scenario_sampling.h"
#include "gen/setting_lists.h"
#include "scene/bvh.h"

namespace vbsim {

std::array<float, 16> far_translation(int k) {
  const float t = std::ldexp(1.0f, k);
  return {1, 0, 0, t, 0, 1, 0, t, 0, 0, 1, t, 0, 0, 0, 1};
}

std::vector<ScenarioCase> generate_far_instance_scenario(const ScenarioSettings& s) {
  const std::vector<double> ks = number_list(s, "k", {20});
  const std::string scene_file = s.text("scene", std::string(VBSIM_TRACES_DIR) + "/bunny/bunny.obj");
  PathsParams p;
  p.max_depth = static_cast<int>(s.integer("depth", 2));
  p.ior = static_cast<float>(s.number("ior", 1.5));
  p.hit_points = paths_hit_point_mode(s.text("hitpoint", "both"));
  if (p.max_depth < 0) throw std::runtime_error("option '--set depth': must be >= 0");
  if (!(p.ior > 0)) throw std::runtime_error("option '--set ior': must be > 0");
  for (double k : ks)
    if (k != std::floor(k) || k < 0 || k > 24)
      throw std::runtime_error(fmt::format("option '--set k': {} is not an integer from 0 to 24", k));
  p.paths = static_cast<int>(rays_per_case(s.rays(), ks.size()));

  std::vector<ScenarioCase> cases;
  for (size_t i = 0; i < ks.size(); ++i) {
    const int k = static_cast<int>(ks[i]);
    ScenarioCase c;
    c.name = fmt::format("far-instance-k{}", k);
    c.scene_file = scene_file;
    c.transform = far_translation(k);
    const Scene scene = load_scene(scene_file, c.transform);  // as a replay loads it
    const Bvh bvh = build_bvh(scene);
    p.seed = s.seed() + i;
    GeneratedPaths g = generate_paths(scene, bvh, p);
    c.light = g.light;
    c.rays = std::move(g.rays);
    c.description = fmt::format("{} translated by 2^{} along (1,1,1) by the header transform; {} camera paths of "
                                "depth {} with shadow, reflect, refract and diffuse children",
                                std::filesystem::path(scene_file).filename().string(), k, p.paths, p.max_depth);
    cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace vbsim
