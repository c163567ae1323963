#include "gen/refraction_scenario.h"

#include <fmt/format.h>

#include <stdexcept>

#include "gen/mesh_shapes.h"
#include "gen/scenario_sampling.h"
#include "gen/surface_children.h"
#include "scene/bvh.h"

namespace vbsim {

namespace {

struct GlassParams {
  int64_t cameras;
  double ior;
  int bounces;
  HitPointSetting hitpoint;
};

ScenarioCase glass_case(const std::string& object, const Mesh& mesh, const GlassParams& p, SeededRandom& rng) {
  const Scene scene = make_scene(mesh.triangles, mesh.normals);
  const Bvh bvh = build_bvh(scene);
  const RendererTracer tracer(scene, bvh);
  TraceRays out;
  int64_t tir = 0;
  for (int64_t i = 0; i < p.cameras; ++i) {
    TraceRay camera;
    camera.o = 3.5f * rng.unit_vector();
    camera.d = 0.8f * static_cast<float>(rng.uniform()) * rng.unit_vector() - camera.o;
    TraceRay ray = out.add(camera);
    for (int bounce = 0; bounce <= p.bounces; ++bounce) {
      const Hit h = tracer.trace(ray);
      if (!h.valid()) break;
      const SurfaceChildren kids = glass_children(ray, h, scene, p.ior, p.hitpoint.rule(i));
      const TraceRay reflected = out.add(kids.reflect);
      if (bounce == p.bounces) break;
      tir += kids.total_internal;
      // After total internal reflection the path follows the reflection.
      ray = kids.total_internal ? reflected : out.add(kids.transmit);
    }
  }
  ScenarioCase c;
  c.name = "refraction-" + object;
  c.triangles = mesh.triangles;
  c.normals = mesh.normals;
  c.rays = std::move(out.rays);
  c.description = fmt::format("closed glass {} (ior {}), {} camera rays followed through up to {} transmissions; "
                              "{} total internal reflections",
                              object, p.ior, p.cameras, p.bounces, tir);
  return c;
}

}  // namespace

std::vector<ScenarioCase> generate_refraction_scenario(const ScenarioSettings& s) {
  const std::string objects = s.text("objects", "sphere,box");
  GlassParams p{0, s.number("ior", 1.5), static_cast<int>(s.integer("bounces", 4)), HitPointSetting(s)};
  const int64_t segments = s.integer("segments", 32);
  if (!(p.ior > 0)) throw std::runtime_error("option '--set ior': must be > 0");
  if (p.bounces < 0 || p.bounces > 64) throw std::runtime_error("option '--set bounces': must be from 0 to 64");
  if (segments < 4 || segments > 4096 || segments % 2)
    throw std::runtime_error("option '--set segments': must be an even integer from 4 to 4096");
  std::vector<std::pair<std::string, Mesh>> meshes;
  size_t start = 0;
  while (start <= objects.size()) {
    const size_t comma = std::min(objects.find(',', start), objects.size());
    const std::string name = objects.substr(start, comma - start);
    if (name == "sphere") meshes.emplace_back(name, uv_sphere({0, 0, 0}, 1.0, static_cast<int>(segments), static_cast<int>(segments / 2)));
    else if (name == "box") meshes.emplace_back(name, box_mesh({-1, -1, -1}, {1, 1, 1}));
    else throw std::runtime_error(fmt::format("option '--set objects={}': '{}' is not sphere or box", objects, name));
    start = comma + 1;
  }
  p.cameras = rays_per_case(s.rays(), meshes.size());
  SeededRandom rng(s.seed());
  std::vector<ScenarioCase> cases;
  for (const auto& [name, mesh] : meshes) cases.push_back(glass_case(name, mesh, p, rng));
  return cases;
}

}  // namespace vbsim
