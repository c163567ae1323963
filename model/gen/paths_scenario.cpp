#include "gen/paths_scenario.h"

#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>

#include "gen/paths_generator.h"
#include "scene/bvh.h"

namespace vbsim {

std::vector<ScenarioCase> generate_paths_scenario(const ScenarioSettings& s) {
  const std::string scene_file = s.text("scene", std::string(VBSIM_TRACES_DIR) + "/bunny/bunny.obj");
  PathsParams p;
  p.paths = static_cast<int>(s.rays());
  p.max_depth = static_cast<int>(s.integer("depth", 3));
  p.ior = static_cast<float>(s.number("ior", 1.5));
  p.seed = s.seed();
  p.hit_points = paths_hit_point_mode(s.text("hitpoint", "both"));
  if (p.paths <= 0) throw std::runtime_error("option '--rays': must be > 0");
  if (p.max_depth < 0) throw std::runtime_error("option '--set depth': must be >= 0");
  if (!(p.ior > 0)) throw std::runtime_error("option '--set ior': must be > 0");

  const Scene scene = load_scene(scene_file);
  const Bvh bvh = build_bvh(scene);
  GeneratedPaths g = generate_paths(scene, bvh, p);
  ScenarioCase c;
  c.name = "paths";
  c.scene_file = scene_file;
  c.light = g.light;
  c.rays = std::move(g.rays);
  c.description = fmt::format(
      "{} camera paths over {}: primary, shadow, reflect, refract and diffuse rays; hit points by ray "
      "equation on even paths, barycentric on odd ones; expect from the exact oracle",
      p.paths, std::filesystem::path(scene_file).filename().string());
  return {std::move(c)};
}

}  // namespace vbsim
