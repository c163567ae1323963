#include "gen/layers_scenario.h"

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <stdexcept>

#include "gen/mesh_shapes.h"
#include "gen/scenario_sampling.h"
#include "gen/setting_lists.h"
#include "gen/surface_children.h"
#include "scene/bvh.h"

namespace vbsim {

namespace {

struct LayerSetup {
  std::string name;
  std::string description;
  Mesh mesh;
  Vec3f light;
  std::function<TraceRay(SeededRandom&)> camera;  ///< a camera ray toward the upper surface
};

struct LayerParams {
  int64_t cameras;
  double ior;
  HitPointSetting hitpoint;
};

/// Camera rays, each followed (when it hits) by its reflection, its
/// refraction (or total internal reflection) and a shadow ray to the light.
ScenarioCase layer_case(const LayerSetup& setup, const LayerParams& p, SeededRandom& rng) {
  const Scene scene = make_scene(setup.mesh.triangles, setup.mesh.normals);
  const Bvh bvh = build_bvh(scene);
  const RendererTracer tracer(scene, bvh);
  TraceRays out;
  for (int64_t i = 0; i < p.cameras; ++i) {
    const TraceRay& parent = out.add(setup.camera(rng));
    const Hit h = tracer.trace(parent);
    if (!h.valid()) continue;
    const RendererHitPoint rule = p.hitpoint.rule(i);
    const SurfaceChildren kids = glass_children(parent, h, scene, p.ior, rule);
    const TraceRay parent_copy = parent;  // `out` may reallocate below
    out.add(kids.transmit);
    out.add(kids.reflect);
    out.add(shadow_child_at_hit(parent_copy, h, scene, setup.light, rule));
  }
  ScenarioCase c;
  c.name = setup.name;
  c.triangles = setup.mesh.triangles;
  c.normals = setup.mesh.normals;
  c.light = setup.light;
  c.rays = std::move(out.rays);
  c.description = setup.description + fmt::format("; {} camera rays, each with refraction, reflection and shadow children", p.cameras);
  return c;
}

/// Camera ray from above toward a random point of the upper square of the
/// left (x < 0) or right (x > 0) pair, alternately.
TraceRay camera_from_above(SeededRandom& rng, float top_z, int64_t& count) {
  const double side = (count++ % 2 == 0) ? -1.0 : 1.0;
  const Vec3f target{static_cast<float>(side * rng.uniform(0.1, 0.9)), static_cast<float>(rng.uniform(-0.9, 0.9)), top_z};
  TraceRay r;
  r.o = target + Vec3f{static_cast<float>(rng.uniform(-1, 1)), static_cast<float>(rng.uniform(-1, 1)), 2.0f};
  r.d = target - r.o;
  return r;
}

LayerSetup separated_planes(double separation, double offset, float z) {
  const float bottom = z, top = static_cast<float>(z + separation * offset);
  LayerSetup s;
  s.name = fmt::format("layers-sep{:.3g}", separation);
  s.description = fmt::format(
      "two pairs of parallel squares, the upper at z={} ({:g} x offset {:g} = {:g} above z={}): left "
      "both facing +z, right a sheet (upper +z, lower -z)",
      top, separation, offset, double(top) - double(bottom), bottom);
  s.mesh = quad_mesh({-1, -1, top}, {0.98f, 0, 0}, {0, 2, 0});          // left upper, +z
  s.mesh.append(quad_mesh({-1, -1, bottom}, {0.98f, 0, 0}, {0, 2, 0}));  // left lower, +z
  s.mesh.append(quad_mesh({0.02f, -1, top}, {0.98f, 0, 0}, {0, 2, 0}));  // right upper, +z
  s.mesh.append(quad_mesh({0.02f, -1, bottom}, {0, 2, 0}, {0.98f, 0, 0}));  // right lower, -z
  s.light = {0, 0, z - 5.0f};
  auto count = std::make_shared<int64_t>(0);
  s.camera = [top, count](SeededRandom& rng) { return camera_from_above(rng, top, *count); };
  return s;
}

LayerSetup nested_spheres(double shell, int segments) {
  LayerSetup s;
  s.name = "layers-nested-spheres";
  s.description = fmt::format("UV sphere r=1 inside one of r=1+{:g}, {} segments; light at the centre", shell, segments);
  s.mesh = uv_sphere({0, 0, 0}, 1.0 + shell, segments, segments / 2);
  s.mesh.append(uv_sphere({0, 0, 0}, 1.0, segments, segments / 2));
  s.light = {0, 0, 0};
  s.camera = [](SeededRandom& rng) {
    const Vec3f u = rng.unit_vector();
    TraceRay r;
    r.o = 3.0f * u + 0.5f * rng.unit_vector();
    r.d = u - r.o;
    return r;
  };
  return s;
}

LayerSetup sphere_on_plane(int segments) {
  const int rings = segments / 2;
  // The fan around the bottom pole rises at slope tan(pi / (2 rings)); camera
  // rays come in at half that slope, so they reach the plane under the sphere.
  const double slope = 0.5 * std::tan(M_PI / (2.0 * rings));
  LayerSetup s;
  s.name = "layers-sphere-on-plane";
  s.description = fmt::format(
      "UV sphere r=1, {} segments, resting with its pole on the plane z=0; grazing camera rays to points "
      "1e-4 to 1e-2 from the contact; light above",
      segments);
  s.mesh = quad_mesh({-2, -2, 0}, {4, 0, 0}, {0, 4, 0});
  s.mesh.append(uv_sphere({0, 0, 1}, 1.0, segments, rings));
  s.light = {0, 0, 10};
  s.camera = [slope](SeededRandom& rng) {
    const double rho = std::pow(10.0, rng.uniform(-4.0, -2.0)), phi = rng.uniform(0, 2 * M_PI);
    const Vec3f target{static_cast<float>(rho * std::cos(phi)), static_cast<float>(rho * std::sin(phi)), 0.0f};
    TraceRay r;
    r.o = target + Vec3f{static_cast<float>(20 * std::cos(phi)), static_cast<float>(20 * std::sin(phi)),
                         static_cast<float>(20 * slope)};
    r.d = target - r.o;
    return r;
  };
  return s;
}

}  // namespace

std::vector<ScenarioCase> generate_layers_scenario(const ScenarioSettings& s) {
  const std::vector<double> separations = number_list(s, "separation", log_spaced(0.5, 10, 5));
  const double offset = s.number("offset", 1e-4);
  const float z = static_cast<float>(s.number("z", 1.0));
  const double shell = s.number("shell", 4e-5);
  const int64_t segments = s.integer("segments", 32);
  LayerParams p{0, s.number("ior", 1.5), HitPointSetting(s)};
  for (double sep : separations)
    if (!(sep > 0)) throw std::runtime_error(fmt::format("option '--set separation': {} is not > 0", sep));
  if (!(offset > 0)) throw std::runtime_error("option '--set offset': must be > 0");
  if (!(shell > 0)) throw std::runtime_error("option '--set shell': must be > 0");
  if (segments < 4 || segments > 4096 || segments % 2)
    throw std::runtime_error("option '--set segments': must be an even integer from 4 to 4096");
  if (!(p.ior > 0)) throw std::runtime_error("option '--set ior': must be > 0");

  std::vector<LayerSetup> setups;
  for (double sep : separations) setups.push_back(separated_planes(sep, offset, z));
  setups.push_back(nested_spheres(shell, static_cast<int>(segments)));
  setups.push_back(sphere_on_plane(static_cast<int>(segments)));
  p.cameras = rays_per_case(s.rays(), setups.size());
  SeededRandom rng(s.seed());
  std::vector<ScenarioCase> cases;
  for (const LayerSetup& setup : setups) cases.push_back(layer_case(setup, p, rng));
  return cases;
}

}  // namespace vbsim
