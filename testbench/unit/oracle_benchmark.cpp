// Oracle throughput benchmark (hidden: run with `vbsim_tests "[.oracle-bench]"`).
// Scenes: a closed UV sphere of about 5k triangles over a floor, and the bundled
// bunny; rays: camera rays, their reflection rays from the exact parent plane
// point, and shadow rays toward a light (tmax = 1). BVH: build_bvh (SAH).
// Prints rays per second; asserts a sample of answers against brute force.
#include <catch2/catch.hpp>
#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <random>

#include "exact/expected_answers.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "oracle_test_support.h"

using namespace vbsim;

namespace {

std::vector<Triangle> uv_sphere(int rings, int segments, float radius) {
  std::vector<Vec3f> p;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double th = M_PI * r / rings, ph = 2 * M_PI * s / segments;
      p.push_back({static_cast<float>(radius * std::sin(th) * std::cos(ph)),
                   static_cast<float>(radius * std::cos(th)),
                   static_cast<float>(radius * std::sin(th) * std::sin(ph))});
    }
  std::vector<Triangle> tris;
  auto at = [&](int r, int s) { return p[static_cast<size_t>(r * segments + (s % segments))]; };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      if (r > 0) tris.push_back({at(r, s), at(r, s + 1), at(r + 1, s)});
      if (r + 1 < rings) tris.push_back({at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)});
    }
  return tris;
}

// Builds the camera / reflection / shadow trace, times the oracle over it and
// checks a sample of answers against brute force.
void run_workload(const char* name, const Scene& scene, Vec3f eye, Vec3f look, float spread, Vec3f light) {
  const Bvh bvh = build_bvh(scene);
  const Oracle oracle(scene, bvh);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> screen(-spread, spread);
  std::vector<TraceRay> trace;
  const int cameras = 4000;
  for (int i = 0; i < cameras; ++i) {
    TraceRay r;
    r.id = i;
    r.o = eye;
    r.d = look + Vec3f{screen(rng), screen(rng), screen(rng)} - eye;
    trace.push_back(r);
  }
  for (int i = 0; i < cameras; ++i) {
    const TraceRay cam = trace[static_cast<size_t>(i)];
    const OracleAnswer a = oracle.answer(intended_ray(cam, scene, nullptr));
    if (a.prim < 0) continue;
    const Triangle& t = scene.triangles[static_cast<size_t>(a.prim)];
    const Vec3f p = cam.o + static_cast<float>(a.t) * cam.d;
    const Vec3f n = normalize(geometric_normal(t));
    TraceRay refl;
    refl.id = static_cast<int64_t>(trace.size());
    refl.parent = cam.id;
    refl.kind = RayKind::Reflect;
    refl.parent_prim = a.prim;
    refl.o = p;
    refl.d = cam.d - (2 * dot(cam.d, n)) * n;
    trace.push_back(refl);
    TraceRay shadow = refl;
    shadow.id = static_cast<int64_t>(trace.size());
    shadow.kind = RayKind::Shadow;
    shadow.d = light - p;
    shadow.tmax = 1;
    trace.push_back(shadow);
  }
  const ParentRays parents = collect_parent_rays(trace);

  const auto start = std::chrono::steady_clock::now();
  int hits = 0;
  for (const TraceRay& r : trace) hits += oracle.answer(intended_ray(r, scene, find_parent(parents, r.parent))).prim >= 0;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("oracle, {}: {} rays ({} hits) on {} triangles in {:.3f} s: {:.0f} rays/s\n", name, trace.size(),
             hits, scene.size(), seconds, trace.size() / seconds);

  for (size_t i = 0; i < trace.size(); i += trace.size() / 12) {
    const ExactRay r = intended_ray(trace[i], scene, find_parent(parents, trace[i].parent));
    REQUIRE(oracle.closest_ties(r) == test::reference_closest(scene, r).ties);
  }
  CHECK(hits > cameras / 2);
}

}  // namespace

TEST_CASE("oracle throughput on a 5k-triangle sphere and on the bunny", "[.oracle-bench]") {
  std::vector<Triangle> tris = uv_sphere(50, 50, 1.0f);
  tris.push_back({{-4, -1, -4}, {4, -1, -4}, {-4, -1, 4}});
  tris.push_back({{4, -1, -4}, {4, -1, 4}, {-4, -1, 4}});
  run_workload("sphere", make_scene(tris), {0.3f, 0.4f, -4}, {0, 0, 0}, 1.3f, {2, 5, -3});
  const Scene bunny = load_scene(VBSIM_SOURCE_DIR "/traces/bunny/bunny.obj");
  const Vec3f c = 0.5f * (bunny.bounds.lo + bunny.bounds.hi);
  const float r = length(bunny.bounds.hi - bunny.bounds.lo);
  run_workload("bunny", bunny, c + Vec3f{0.1f * r, 0.2f * r, 1.5f * r}, c, 0.3f * r, c + Vec3f{r, 2 * r, r});
}
