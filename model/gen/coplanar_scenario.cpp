#include "gen/coplanar_scenario.h"

#include <fmt/format.h>

#include "gen/optics.h"
#include "gen/scenario_sampling.h"
#include "scene/bvh.h"

namespace vbsim {

std::vector<ScenarioCase> generate_coplanar_scenario(const ScenarioSettings& s) {
  const float z = static_cast<float>(s.number("z", 0.5));
  const HitPointSetting hitpoint(s);
  const int64_t cameras = rays_per_case(s.rays(), 1);
  const Vec3f a{0, 0, z}, b{1, 0, z}, c{0, 1, z}, d{1, 1, z};
  const std::vector<Triangle> tris = {
      {a, b, c}, {a, b, c}, {a, c, b}, {b, d, c}, {{0.25f, 0.25f, z}, {1.25f, 0.25f, z}, {0.25f, 1.25f, z}}};
  const Scene scene = make_scene(tris);
  const Bvh bvh = build_bvh(scene);
  const RendererTracer tracer(scene, bvh);
  const Vec3f light{0.5f, 0.5f, z + 10.0f};
  SeededRandom rng(s.seed());
  TraceRays out;
  for (int64_t i = 0; i < cameras; ++i) {
    const Vec3f target{static_cast<float>(rng.uniform(0, 1.2)), static_cast<float>(rng.uniform(0, 1.2)), z};
    TraceRay camera;
    if (i % 5 == 4) {  // in the plane
      camera.o = {-1.0f, static_cast<float>(rng.uniform(-0.5, 1.5)), z};
      camera.d = Vec3f{target.x, target.y, z} - camera.o;
      out.add(camera);
      continue;
    }
    camera.o = target + Vec3f{static_cast<float>(rng.uniform(-1, 1)), static_cast<float>(rng.uniform(-1, 1)), 2.0f};
    camera.d = target - camera.o;
    const TraceRay parent = out.add(camera);
    const Hit h = tracer.trace(parent);
    if (!h.valid()) continue;
    const RendererHitPoint rule = hitpoint.rule(i);
    const DVec3 up{0, 0, 1};
    out.add(child_at_hit(parent, h, scene, RayKind::Reflect, to_vec3f(mirror(dunit(to_dvec(parent.d)), up)), rule));
    out.add(child_at_hit(parent, h, scene, RayKind::Diffuse, to_vec3f(dunit(up + to_dvec(rng.unit_vector()))), rule));
    out.add(shadow_child_at_hit(parent, h, scene, light, rule));
  }
  ScenarioCase sc;
  sc.name = "coplanar";
  sc.triangles = tris;
  sc.light = light;
  sc.rays = std::move(out.rays);
  sc.description = fmt::format(
      "coplanar stack at z={}: a triangle, its duplicate, its reversed duplicate, its neighbour and an "
      "overlapping one; {} camera rays (every fifth in the plane), with reflect, diffuse and shadow children",
      z, cameras);
  return {std::move(sc)};
}

}  // namespace vbsim
