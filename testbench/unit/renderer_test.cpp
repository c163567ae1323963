// The renderer: acne where a method without self-intersection handling
// re-hits the surface, none with robust methods, leaks where an offset jumps
// over a real occluder, and the same picture from every method that makes no
// error. Scene: render_test_scene.h.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <unordered_map>
#include <utility>

#include "datapath/hit_point.h"
#include "datapath/testers.h"
#include "render/render_colours.h"
#include "render/renderer.h"
#include "render_test_scene.h"

using namespace vbsim;

namespace {

struct Fixture {
  Scene scene = make_scene(test::render_test_triangles());
  Bvh bvh = build_bvh(scene);
};

RenderResult render_with(const Fixture& f, const std::string& method, int size = 8,
                         float offset_direction_eps = 1e-4f) {
  ReplayOptions opt;
  std::string error;
  REQUIRE(parse_method(method, opt.method, error));
  opt.method.offset_direction_eps = offset_direction_eps;
  if (method == "validity-bit") opt.method.avoidance.policy = AvoidancePolicy::Vote;
  RenderSettings rs;
  rs.width = rs.height = size;
  REQUIRE(parse_render_light(test::kRenderTestLight, rs.light, error));
  return render_scene(f.scene, f.bvh, opt, rs);
}

bool on_ground(int32_t prim) { return prim == 0 || prim == 1; }

/// True when the tester, run on every triangle of the scene without BVH,
/// method or verdict, hits one within `near` of the ray's origin.
bool rehits_near(const Scene& scene, const Ray& ray, float near) {
  const ThreeHalfPlaneTester tester(ray);
  for (const Triangle& tri : scene.triangles) {
    Hit h;
    if (tester.intersect(tri, ray.tmax, h) && h.t * length(ray.d) < near) return true;
  }
  return false;
}

/// The reference renderer's settings (children from the exact answers: the
/// picture is the scene's, not a method's) for `integrator` at 24 x 24.
RenderSettings exact_render(RenderIntegrator integrator) {
  RenderSettings rs;
  rs.width = rs.height = 24;
  rs.integrator = integrator;
  rs.children_from_exact = true;
  return rs;
}

ReplayOptions validity_bit() {
  ReplayOptions opt;
  std::string error;
  REQUIRE(parse_method("validity-bit", opt.method, error));
  return opt;
}

}  // namespace

TEST_CASE("method none shows acne on surface pixels only in the acne colour and no leaks", "[render]") {
  const Fixture f;
  const RenderResult r = render_with(f, "none");
  CHECK(r.acne_pixels > 0);
  CHECK(r.leak_pixels == 0);
  CHECK(r.unscored_rays == 0);
  int ground_pixels = 0;
  for (size_t i = 0; i < r.marks.size(); ++i) {
    ground_pixels += on_ground(r.primary_prim[i]);
    // Only surface pixels spawn shadow and bounce rays; the occluder's top is
    // lit too, so acne may sit on either quad, never on the background.
    if (r.marks[i] & kMarkAcne) CHECK(r.primary_prim[i] >= 0);
    const Rgb8 e{r.errors[3 * i], r.errors[3 * i + 1], r.errors[3 * i + 2]};
    CHECK((e == kAcneRgb) == (r.marks[i] == kMarkAcne));
  }
  CHECK(ground_pixels >= 10);  // the framing shows the ground in a quarter of the image
  // Acne comes from shadow and mirror rays re-hitting their own plane.
  const KindStats& shadow = r.stats.by_kind[static_cast<int>(RayKind::Shadow)];
  CHECK(shadow.verdicts[static_cast<int>(Verdict::SelfHit)] > 0);
}

TEST_CASE("method none: acne exactly where a brute-force tester loop re-hits the quad at the origin", "[render]") {
  // Independent of the BVH, the emission code, the oracle and the verdicts:
  // rebuild each surface pixel's shadow ray (traced where the light is on the
  // camera's side) and mirror ray from the primary hit's barycentric point, and
  // test them against all four triangles. The nearest real occluder is 0.8
  // away, so a hit within 1e-4 is the ray re-hitting the surface it left: acne.
  // (Whether the tester re-hits is not decided by the exact side of the plane
  // the rounded origin lies on: a float32 tester's t near 0 has its own error.)
  const Fixture f;
  const RenderResult r = render_with(f, "none");
  const PinholeCamera camera(CameraSpec{}, f.scene.bounds, 8, 8);
  RenderLight light;
  std::string error;
  REQUIRE(parse_render_light(test::kRenderTestLight, light, error));
  int predicted = 0;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      const size_t i = size_t(y) * 8 + size_t(x);
      const int32_t prim = r.primary_prim[i];
      if (prim < 0) continue;
      Ray primary;
      primary.o = camera.eye();
      primary.d = camera.direction(x, y);
      Hit h;
      const Triangle& tri = f.scene.triangles[prim];
      REQUIRE(ThreeHalfPlaneTester(primary).intersect(tri, primary.tmax, h));
      const Vec3f dn = normalize(primary.d), ng = normalize(geometric_normal(tri));
      const Vec3f n = dot(dn, ng) < 0.0f ? ng : -ng;
      Ray shadow, mirror;
      shadow.o = mirror.o = hit_point_barycentric(tri, h.u, h.v);
      shadow.d = light.value;
      mirror.d = dn - (2.0f * dot(dn, n)) * n;
      const bool lit_side = dot(n, normalize(light.value)) > 0.0f;
      const bool acne = (lit_side && rehits_near(f.scene, shadow, 1e-4f)) || rehits_near(f.scene, mirror, 1e-4f);
      predicted += acne;
      INFO("pixel " << x << "," << y << " triangle " << prim);
      CHECK(acne == ((r.marks[i] & kMarkAcne) != 0));
    }
  }
  CHECK(predicted > 0);
  CHECK(r.acne_pixels == uint64_t(predicted));
}

TEST_CASE("robust methods render without acne or leaks and agree pixel for pixel", "[render]") {
  const Fixture f;
  const RenderResult ref = render_with(f, "offset-errbound");
  CHECK(ref.acne_pixels == 0);
  CHECK(ref.leak_pixels == 0);
  for (const char* m : {"validity-bit", "primid", "offset-adaptive"}) {
    INFO(m);
    const RenderResult r = render_with(f, m);
    CHECK(r.acne_pixels == 0);
    CHECK(r.leak_pixels == 0);
    // Correct visibility everywhere: the same shaded image, up to one level of
    // rounding where a bounce hits at a slightly different (u, v).
    int worst = 0;
    for (size_t i = 0; i < r.image.size(); ++i) worst = std::max(worst, std::abs(r.image[i] - ref.image[i]));
    CHECK(worst <= 1);
  }
  // The occluder really shades part of the ground: some ground pixels get no
  // direct light (their colour is the ambient term plus the bounce's share).
  const RenderResult none = render_with(f, "none");
  int differing = 0;
  for (size_t i = 0; i < ref.marks.size(); ++i)
    differing += none.marks[i] != 0 && std::abs(none.image[3 * i] - ref.image[3 * i]) > 1;
  CHECK(differing > 0);  // acne darkens pixels the robust render lights
}

TEST_CASE("an offset longer than the occluder's height leaks light under it", "[render]") {
  const Fixture f;
  const RenderResult ref = render_with(f, "offset-errbound", 16);
  // Offsetting 2 units along the ray starts shadow rays beyond the occluder,
  // 0.8 above the ground: every pixel it shadows lights up and is marked.
  const RenderResult leaky = render_with(f, "offset-direction", 16, 2.0f);
  CHECK(leaky.leak_pixels > 0);
  CHECK(leaky.acne_pixels == 0);
  for (size_t i = 0; i < leaky.marks.size(); ++i) {
    const bool brighter = leaky.image[3 * i] > ref.image[3 * i] + 1;
    if (brighter) CHECK((leaky.marks[i] & kMarkLeak) != 0);
    if (leaky.marks[i] == 0) CHECK(std::abs(leaky.image[3 * i] - ref.image[3 * i]) <= 1);
  }
}

TEST_CASE("sign-only lets light through the occluder parallel to the ground", "[render]") {
  // The occluder faces the way the ground does, so a shadow ray leaving the
  // ground meets it with the same front/back bit as its parent's: a suspect,
  // which sign-only rejects (so do mirror rays meeting its underside). The
  // leaking pixels are exactly the ground pixels it renders brighter than the
  // exact render does.
  const Fixture f;
  const RenderResult ref = render_with(f, "offset-errbound", 16);
  const RenderResult r = render_with(f, "sign-only", 16);
  CHECK(r.acne_pixels == 0);
  CHECK(r.leak_pixels > 0);
  for (size_t i = 0; i < r.marks.size(); ++i) {
    INFO("pixel " << i);
    const bool lit_up = on_ground(ref.primary_prim[i]) && r.image[3 * i] > ref.image[3 * i] + 1;
    CHECK(lit_up == ((r.marks[i] & kMarkLeak) != 0));
  }
}

TEST_CASE("render refuses a zero image size", "[render]") {
  const Fixture f;
  RenderSettings rs;
  rs.width = 0;
  CHECK_THROWS_WITH(render_scene(f.scene, f.bvh, ReplayOptions{}, rs), Catch::Contains("image size"));
}

TEST_CASE("ambient occlusion: occlusion rays of the stated length about the normal, dark only under the occluder",
          "[render][ao]") {
  const Fixture f;
  const ReplayOptions opt = validity_bit();
  RenderSettings rs = exact_render(RenderIntegrator::Ao);
  rs.samples = 16;
  const float diagonal = length(f.scene.bounds.hi - f.scene.bounds.lo);
  // The ground's up normal (+y side, where the camera is): Ng of triangle 0.
  const Vec3f up = normalize(geometric_normal(f.scene.triangles[0]));
  for (const float radius : {0.1f, 0.5f}) {
    INFO("ao radius " << radius << " of the diagonal " << diagonal);
    rs.ao_radius = radius;
    std::vector<TraceRay> cast;
    const RenderResult r = render_scene(f.scene, f.bvh, opt, rs, [&](const TraceRay& t) { cast.push_back(t); });
    uint64_t primaries = 0, hits = 0, occlusion = 0;
    for (const TraceRay& t : cast) {
      if (t.kind == RayKind::Primary) {
        ++primaries;
        hits += t.expect_prim >= 0;
        continue;
      }
      REQUIRE(t.kind == RayKind::Shadow);
      ++occlusion;
      CHECK(t.tmax == 1.0f);
      CHECK(t.parent >= 0);
      CHECK(std::abs(length(t.d) - radius * diagonal) <= 1e-5f * diagonal);
      CHECK(dot(t.d, up) > 0.0f);  // every surface the camera sees faces up: the rays leave above it
    }
    CHECK(primaries == 24u * 24u);  // one camera ray a pixel
    CHECK(occlusion == 16 * hits);
    CHECK(r.stats.by_kind[static_cast<int>(RayKind::Shadow)].rays == occlusion);
    // Each hit pixel is albedo times its unoccluded fraction: exactly albedo
    // where nothing is within reach (the occluder is 0.8 above the ground).
    const Rgb8 full = to_rgb8(kAlbedo);
    int albedo = 0, darker = 0;
    for (int p = 0; p < 24 * 24; ++p) {
      if (r.primary_prim[p] < 0) continue;
      const bool same = r.image[3 * p] == full[0] && r.image[3 * p + 1] == full[1] && r.image[3 * p + 2] == full[2];
      albedo += same;
      darker += !same && r.image[3 * p] < full[0];
      if (r.primary_prim[p] >= 2) CHECK(same);  // the occluder's top: open sky above it
    }
    CHECK(albedo + darker == static_cast<int>(hits));
    if (radius * diagonal < 0.8f) CHECK(darker == 0);
    else CHECK(darker > 0);  // the ground beside and under the occluder's edge
  }
  rs.ao_radius = 0.0f;
  CHECK_THROWS_WITH(render_scene(f.scene, f.bvh, opt, rs), Catch::Contains("ao radius"));
}

namespace {

/// A cube [-1, 1]^3 of 12 triangles wound outward (Ng points out of it).
Scene outward_cube() {
  std::vector<Triangle> tris;
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      auto corner = [&](float a, float b) {
        Vec3f p{0, 0, 0};
        p[axis] = side;
        p[u] = a;
        p[v] = b;
        return p;
      };
      const Vec3f c00 = corner(-1, -1), c10 = corner(1, -1), c11 = corner(1, 1), c01 = corner(-1, 1);
      if (side > 0) tris.insert(tris.end(), {{c00, c10, c11}, {c00, c11, c01}});
      else tris.insert(tris.end(), {{c00, c11, c10}, {c00, c01, c11}});
    }
  return make_scene(tris);
}

/// Checks every child ray the glass render of `scene` cast against Snell's
/// law and the critical angle; returns (refractions, reflections).
std::pair<int, int> check_glass_rays(const Scene& scene, const Bvh& bvh, RenderResult& r) {
  RenderSettings rs = exact_render(RenderIntegrator::Glass);
  rs.max_bounces = 5;
  std::vector<TraceRay> cast;
  r = render_scene(scene, bvh, validity_bit(), rs, [&](const TraceRay& t) { cast.push_back(t); });
  std::unordered_map<int64_t, size_t> at;
  for (size_t i = 0; i < cast.size(); ++i) at[cast[i].id] = i;
  int refracted = 0, reflected = 0;
  for (const TraceRay& t : cast) {
    if (t.kind == RayKind::Primary) continue;
    REQUIRE((t.kind == RayKind::Refract || t.kind == RayKind::Reflect));
    const TraceRay& parent = cast.at(at.at(t.parent));
    const Vec3f n = normalize(geometric_normal(scene.triangles[static_cast<size_t>(t.parent_prim)]));
    const Vec3f di = normalize(parent.d), dt = normalize(t.d);
    const bool entering = dot(di, n) < 0.0f;
    const float eta = entering ? 1.0f / kGlassIor : kGlassIor;
    const float sin_i = length(cross(di, n)), sin_t = length(cross(dt, n));
    CHECK(std::abs(length(t.d) - 1.0f) < 1e-5f);
    if (t.kind == RayKind::Refract) {
      ++refracted;
      CHECK(std::abs(sin_t - eta * sin_i) < 1e-4f);        // Snell
      CHECK((dot(dt, n) < 0.0f) == (dot(di, n) < 0.0f));  // through the surface
    } else {
      ++reflected;
      CHECK(!entering);                                     // from inside only
      CHECK(eta * sin_i >= 1.0f - 1e-5f);                   // past the critical angle
      CHECK(std::abs(sin_t - sin_i) < 1e-4f);               // the mirror direction
      CHECK((dot(dt, n) < 0.0f) != (dot(di, n) < 0.0f));    // back to the side it came from
    }
  }
  return {refracted, reflected};
}

}  // namespace

TEST_CASE("glass: Snell's law at every refraction and reflection only past the critical angle", "[render][glass]") {
  const Fixture f;
  RenderResult r;
  // The ground and the occluder are single sheets: every ray enters them from above and leaves below.
  CHECK(check_glass_rays(f.scene, f.bvh, r).first > 0);
  // Every pixel that sees them: the background times the transmittances, never brighter.
  const Rgb8 sky = to_rgb8(background_linear());
  int glass_pixels = 0;
  for (int p = 0; p < 24 * 24; ++p) {
    if (r.primary_prim[p] < 0) continue;
    ++glass_pixels;
    for (int c = 0; c < 3; ++c) CHECK(r.image[3 * p + c] <= sky[c]);
  }
  CHECK(glass_pixels > 0);
  // A closed cube: rays that entered meet its far faces from inside, some past the critical angle.
  const Scene cube = outward_cube();
  const Bvh cube_bvh = build_bvh(cube);
  const auto [refracted, reflected] = check_glass_rays(cube, cube_bvh, r);
  CHECK(refracted > 0);
  CHECK(reflected > 0);
  RenderSettings rs;
  rs.integrator = RenderIntegrator::Glass;
  rs.samples = 2;
  CHECK_THROWS_WITH(render_scene(f.scene, f.bvh, ReplayOptions{}, rs), Catch::Contains("one camera ray a pixel"));
}
