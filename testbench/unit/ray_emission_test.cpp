// Ray emission: sign bit, hit-point modes, fallbacks, tmin and reverse shadow,
// on hand-computed values.
#include <catch2/catch.hpp>

#include <cmath>

#include "datapath/origin_offsets.h"
#include "datapath/testers.h"
#include "replay/ray_emission.h"

using namespace vbsim;

namespace {
// Floor in z = 0 with Ng = +z, and a wall in x = 2 with Ng = -x.
Scene two_triangles() {
  return make_scene({Triangle{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}, Triangle{{2, 0, 0}, {2, 0, 4}, {2, 4, 0}}});
}

TraceRay child_of(int64_t parent, int32_t prim, Vec3f o, Vec3f d) {
  TraceRay tr;
  tr.id = 7;
  tr.parent = parent;
  tr.kind = RayKind::Reflect;
  tr.parent_prim = prim;
  tr.o = o;
  tr.d = d;
  return tr;
}
}  // namespace

TEST_CASE("the parent sign bit is computed from Ng when the trace omits it", "[emission]") {
  const Scene scene = two_triangles();
  REQUIRE(geometric_normal(scene.triangles[1]).x < 0);
  CHECK(parent_sign_bit(child_of(0, 0, {1, 1, 0}, {0, 0, 1}), scene) == 0);   // leaves along Ng
  CHECK(parent_sign_bit(child_of(0, 0, {1, 1, 0}, {0, 0, -1}), scene) == 1);  // refracts through
  CHECK(parent_sign_bit(child_of(0, 1, {2, 1, 1}, {1, 0, 0}), scene) == 1);   // wall: Ng = -x
  TraceRay given = child_of(0, 0, {1, 1, 0}, {0, 0, 1});
  given.sign = 1;  // a given bit is carried as is
  CHECK(parent_sign_bit(given, scene) == 1);
  TraceRay camera;
  camera.d = {0, 0, -1};
  CHECK(parent_sign_bit(camera, scene) == 0);
}

TEST_CASE("hit-point modes recompute the origin from the parent's data", "[emission]") {
  const Scene scene = two_triangles();
  ParentRays parents;
  parents[3] = {Vec3f{1, 1, 5}, Vec3f{0.5f, 0.25f, -2}};  // meets z = 0 at t = 2.5: (2.25, 1.625, 0)
  TraceRay tr = child_of(3, 0, {9, 9, 9}, {0, 0, 1});
  tr.has_parent_t = true;
  tr.parent_t = 2.5f;
  tr.has_parent_uv = true;
  tr.parent_u = 0.25f;
  tr.parent_v = 0.5f;  // (1-u-v) v0 + u v1 + v v2 = (1, 2, 0)
  ReplayOptions opt;
  CHECK(emit_ray(tr, scene, opt, find_parent(parents, tr.parent)).ray.o == Vec3f{9, 9, 9});  // given
  opt.hit_point = HitPointMode::Ray;
  EmittedRay er = emit_ray(tr, scene, opt, find_parent(parents, tr.parent));
  CHECK(er.ray.o == Vec3f{2.25f, 1.625f, 0});
  CHECK_FALSE(er.emission_fallback);
  opt.hit_point = HitPointMode::Barycentric;
  CHECK(emit_ray(tr, scene, opt, find_parent(parents, tr.parent)).ray.o == Vec3f{1, 2, 0});
  // Without the parent ray, the ray-equation point cannot be formed: fallback.
  opt.hit_point = HitPointMode::Ray;
  er = emit_ray(tr, scene, opt, nullptr);
  CHECK(er.ray.o == Vec3f{9, 9, 9});
  CHECK(er.emission_fallback);
}

TEST_CASE("tmin is a distance: eps over |d|", "[emission]") {
  const Scene scene = two_triangles();
  ReplayOptions opt;
  opt.method.tmin = true;
  opt.method.tmin_eps = 0.5f;
  const EmittedRay er = emit_ray(child_of(0, 0, {1, 1, 0}, {0, 3, 4}), scene, opt, nullptr);
  CHECK(er.ray.tmin == 0.1f);
}

TEST_CASE("reverse-shadow starts at the light and flips direction and sign", "[emission]") {
  const Scene scene = two_triangles();
  ReplayOptions opt;
  opt.method.reverse_shadow = true;
  TraceRay tr = child_of(0, 0, {1, 1, 0}, {0, 0, 6});
  tr.kind = RayKind::Shadow;
  tr.tmax = 1.0f;
  const EmittedRay er = emit_ray(tr, scene, opt, nullptr);
  CHECK(er.reversed);
  CHECK(er.ray.o == Vec3f{1, 1, 6});
  CHECK(er.ray.d == Vec3f{0, 0, -6});
  CHECK(er.ray.tmax == 1.0f);
  CHECK(er.ray.sign == 1);  // forward sign 0 (along Ng), reversed it meets the floor's front
  // Infinite tmax: the light is where the ray leaves the scene's bounds (z = 4 here).
  tr.tmax = INFINITY;
  const EmittedRay far = emit_ray(tr, scene, opt, nullptr);
  CHECK(far.ray.o == Vec3f{1, 1, 4});
  CHECK(far.ray.tmax == Approx(4.0f / 6.0f));
  // Other kinds are not reversed.
  tr.kind = RayKind::Reflect;
  CHECK_FALSE(emit_ray(tr, scene, opt, nullptr).reversed);
}

TEST_CASE("offset-errbound spawns from the barycentrics pbrt's own test finds on the parent ray", "[emission]") {
  const Scene scene = two_triangles();
  ParentRays parents;
  parents[3] = {Vec3f{1, 1, 5}, Vec3f{0.5f, 0.25f, -2}};  // meets the floor at (2.25, 1.625, 0)
  TraceRay tr = child_of(3, 0, {9, 9, 9}, {0, 0, 1});
  tr.has_parent_uv = true;
  tr.parent_u = 0.25f;  // deliberately not the parent ray's hit: (1, 2, 0)
  tr.parent_v = 0.5f;
  ReplayOptions opt;
  opt.method.offset_errbound = true;
  PbrtTriangleHit h;
  Ray parent;
  parent.o = parents[3].o;
  parent.d = parents[3].d;
  REQUIRE(PbrtWatertightTester(parent).intersect_triangle(scene.triangles[0], INFINITY, h));
  OffsetOutcome outcome = OffsetOutcome::Reference;
  const Vec3f want = offset_error_bound({}, scene.triangles[0], h.b0, h.b1, h.b2, nullptr, tr.d, outcome);
  CHECK(want.x == Approx(2.25f));
  CHECK(want.y == Approx(1.625f));
  CHECK(want.z == 0.0f);  // z is exact on the floor: pbrt's bound is 0 there, and so is the offset
  EmittedRay er = emit_ray(tr, scene, opt, find_parent(parents, tr.parent));
  CHECK(er.ray.o == want);
  CHECK_FALSE(er.offset_fallback);
  // Without the parent ray: parent_uv with b0 = 1 - u - v.
  er = emit_ray(tr, scene, opt, nullptr);
  CHECK(er.ray.o.x == Approx(1.0f));
  CHECK(er.ray.o.y == Approx(2.0f));
  CHECK_FALSE(er.emission_fallback);
  // Without either: pbrt's bound on the given point, an emission fallback.
  tr.has_parent_uv = false;
  er = emit_ray(tr, scene, opt, nullptr);
  CHECK(er.emission_fallback);
  CHECK(er.ray.o.z > 9.0f);
}

TEST_CASE("degenerate parent normals are counted as offset fallbacks", "[emission][degenerate]") {
  // A 1e-30 triangle (its float normal underflows) and a collinear one.
  const Scene scene = make_scene({Triangle{{1e-30f, 0, 0}, {0, 1e-30f, 0}, {0, 0, 1e-30f}},
                                  Triangle{{-1, -2, -3}, {-2, -4, -6}, {-3, -6, -9}}});
  ReplayOptions opt;
  opt.method.offset_adaptive = true;
  const TraceRay tiny = child_of(-1, 0, {3e-31f, 3e-31f, 4e-31f}, {1, 1, 1});
  EmittedRay er = emit_ray(tiny, scene, opt, nullptr);
  CHECK(er.offset_fallback);
  CHECK(er.ray.o.x > 1e-6f);  // moved by Listing 6-1's float path along the double normal
  const TraceRay flat = child_of(-1, 1, {-2, -4, -6}, {1, 0, 0});
  er = emit_ray(flat, scene, opt, nullptr);
  CHECK(er.offset_fallback);
  CHECK(er.ray.o == Vec3f{-2, -4, -6});
  opt.method.offset_adaptive = false;
  er = emit_ray(flat, scene, opt, nullptr);
  CHECK_FALSE(er.offset_fallback);
}
