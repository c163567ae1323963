#include "gen/terminator_scenario.h"

#include <fmt/format.h>

#include <stdexcept>

#include "gen/mesh_shapes.h"
#include "gen/optics.h"
#include "gen/scenario_sampling.h"
#include "gen/setting_lists.h"
#include "scene/bvh.h"

namespace vbsim {

namespace {

/// Light direction (unit, double) and the distant point light along it.
const DVec3 kLightDir = dunit({0.8, 0.3, 0.52});
constexpr double kLightDistance = 1000.0;

struct SurfacePoint {
  int32_t prim;
  float u, v;
};

/// A random point of `mesh` in the wanted population (band: shading normal
/// toward the light, geometric normal away; lit: both toward the light).
SurfacePoint sample_point(const Mesh& mesh, bool band, SeededRandom& rng) {
  for (int attempt = 0; attempt < 1000000; ++attempt) {
    SurfacePoint s{static_cast<int32_t>(rng.below(mesh.triangles.size())), 0, 0};
    uniform_barycentrics(rng, s.u, s.v);
    const auto& n = mesh.normals[s.prim];
    const DVec3 ns = to_dvec((1.0f - s.u - s.v) * n[0] + s.u * n[1] + s.v * n[2]);
    const DVec3 ng = to_dvec(geometric_normal(mesh.triangles[s.prim]));
    if (ddot(ns, kLightDir) > 0 && (ddot(ng, kLightDir) > 0) != band) return s;
  }
  throw std::runtime_error("terminator: no surface point found in the wanted population");
}

ScenarioCase terminator_case(int segments, int64_t camera_rays, double band_fraction,
                             const HitPointSetting& hitpoint, SeededRandom& rng) {
  const Mesh mesh = uv_sphere({0, 0, 0}, 1.0, segments, segments / 2);
  const Scene scene = make_scene(mesh.triangles, mesh.normals);
  const Bvh bvh = build_bvh(scene);
  const RendererTracer tracer(scene, bvh);
  const Vec3f light = to_vec3f(kLightDistance * kLightDir);

  TraceRays out;
  int64_t band_count = 0;
  for (int64_t i = 0; i < camera_rays; ++i) {
    const bool band = rng.uniform() < band_fraction;
    const SurfacePoint s = sample_point(mesh, band, rng);
    const Triangle& tri = mesh.triangles[s.prim];
    const Vec3f target = (1.0f - s.u - s.v) * tri.v0 + s.u * tri.v1 + s.v * tri.v2;
    const Vec3f ns = normalize(scene.shading_normal(s.prim, s.u, s.v));
    TraceRay camera;
    camera.o = target + 3.0f * ns;  // looking down the shading normal
    camera.d = target - camera.o;
    const TraceRay& parent = out.add(camera);
    const Hit h = tracer.trace(parent);
    if (!h.valid()) continue;
    band_count += band;
    out.add(shadow_child_at_hit(parent, h, scene, light, hitpoint.rule(i)));
  }
  ScenarioCase c;
  c.name = fmt::format("terminator-s{}", segments);
  c.triangles = mesh.triangles;
  c.normals = mesh.normals;
  c.light = light;
  c.rays = std::move(out.rays);
  c.description = fmt::format(
      "shadow terminator: UV sphere r=1 with {} segments and {} rings, vertex normals; {} camera rays "
      "aimed along the shading normal, each with one shadow ray to a distant light ({} from the band "
      "where the geometric normal faces away, the rest lit)",
      segments, segments / 2, camera_rays, band_count);
  return c;
}

}  // namespace

std::vector<ScenarioCase> generate_terminator_scenario(const ScenarioSettings& s) {
  const std::vector<double> segments = number_list(s, "segments", {8, 16, 32, 64});
  const double band = s.number("band", 0.5);
  const HitPointSetting hitpoint(s);
  if (!(band >= 0 && band <= 1)) throw std::runtime_error("option '--set band': must be in [0, 1]");
  for (double seg : segments)
    if (seg != std::floor(seg) || seg < 4 || seg > 4096 || static_cast<int>(seg) % 2 != 0)
      throw std::runtime_error(
          fmt::format("option '--set segments': {} is not an even integer from 4 to 4096", seg));
  const int64_t per_case = rays_per_case(s.rays(), segments.size());
  SeededRandom rng(s.seed());
  std::vector<ScenarioCase> cases;
  for (double seg : segments) cases.push_back(terminator_case(static_cast<int>(seg), per_case, band, hitpoint, rng));
  return cases;
}

}  // namespace vbsim
