// The gist's shading position and the blog's Möller–Trumbore test against
// their references' own float32 arithmetic (float_emulation.h: every operation
// exact, then rounded once), in the references' operation order.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "datapath/shading_position.h"
#include "datapath/testers.h"
#include "float_emulation.h"

namespace vbsim {
namespace {

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(Vec3f a, Vec3f b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z); }

Vec3f emu_scale(float s, Vec3f a) { return {emu::mul(s, a.x), emu::mul(s, a.y), emu::mul(s, a.z)}; }
Vec3f emu_add(Vec3f a, Vec3f b) { return {emu::add(a.x, b.x), emu::add(a.y, b.y), emu::add(a.z, b.z)}; }

/// The gist's computeShadingPosition, on unit vertex normals (the projection
/// the gist writes needs them; vbsim normalises the stored ones first).
Vec3f emulated_shading_position(Vec3f p, const Triangle& tri, const std::array<Vec3f, 3>& normals, float u, float v,
                                Vec3f ns, bool convex_only) {
  const Vec3f origins[3] = {tri.v0, tri.v1, tri.v2};
  Vec3f proj[3];
  for (int i = 0; i < 3; ++i) {
    const Vec3f n = emu::plain_normalize(normals[i]);
    // projectOnPlane: position - dot(position - origin, normal) * normal
    const float d = emu::plain_dot(emu::sub(p, origins[i]), n);
    proj[i] = emu::sub(p, emu_scale(d, n));
  }
  const float b0 = emu::sub(emu::sub(1, u), v);
  const Vec3f s = emu_add(emu_add(emu_scale(b0, proj[0]), emu_scale(u, proj[1])), emu_scale(v, proj[2]));
  if (!convex_only) return s;
  return emu::plain_dot(emu::sub(s, p), ns) > 0 ? s : p;
}

TEST_CASE("the gist's shading position, operation for operation", "[methods][gist]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> c(-4, 4), w(0.05f, 0.9f);
  int convex = 0, concave = 0;
  for (int i = 0; i < 2000; ++i) {
    const Triangle tri{{c(rng), c(rng), c(rng)}, {c(rng), c(rng), c(rng)}, {c(rng), c(rng), c(rng)}};
    const Vec3f ng = normalize(geometric_normal(tri));
    if (!is_finite(ng)) continue;
    // Vertex normals tilted from Ng both ways: convex and concave patches.
    std::array<Vec3f, 3> normals;
    for (Vec3f& n : normals) n = ng + Vec3f{0.3f * (w(rng) - 0.5f), 0.3f * (w(rng) - 0.5f), 0.3f * (w(rng) - 0.5f)};
    float u = w(rng), v = w(rng);
    if (u + v > 0.95f) u *= 0.5f, v *= 0.5f;
    const Vec3f p = (1.0f - u - v) * tri.v0 + u * tri.v1 + v * tri.v2;
    const Vec3f ns = (1.0f - u - v) * normals[0] + u * normals[1] + v * normals[2];
    INFO("case " << i);
    for (bool convex_only : {true, false})
      REQUIRE(same_bits(shading_position(p, tri, normals, u, v, ns, convex_only),
                        emulated_shading_position(p, tri, normals, u, v, ns, convex_only)));
    (shading_position(p, tri, normals, u, v, ns, true) == p ? concave : convex)++;
  }
  CHECK(convex > 200);   // both branches of the convex test are exercised
  CHECK(concave > 200);
}

// A hand case: a flat triangle z = 0 whose vertex normals lean outward like a
// sphere's: the tangent planes at the vertices lie above the point, so the
// shading position rises above the plane (convex); with the normals leaning
// inward (concave) the convex-only variant keeps the point itself.
TEST_CASE("the gist's shading position rises above a convex patch and keeps a concave one", "[methods][gist]") {
  const Triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const float k = 0.6f, z = 0.8f;  // unit normals (k, 0, z) etc.: 0.36 + 0.64 = 1
  const std::array<Vec3f, 3> out{{{-k, 0, z}, {k, 0, z}, {0, k, z}}};
  const Vec3f p{0.25f, 0.25f, 0};
  const Vec3f ns{0, 0, 1};
  const Vec3f s = shading_position(p, tri, out, 0.25f, 0.25f, ns, true);
  CHECK(s.z > 0.0f);
  CHECK(same_bits(s, emulated_shading_position(p, tri, out, 0.25f, 0.25f, ns, true)));
  const std::array<Vec3f, 3> in{{{k, 0, z}, {-k, 0, z}, {0, -k, z}}};
  CHECK(shading_position(p, tri, in, 0.25f, 0.25f, ns, true) == p);
  CHECK(shading_position(p, tri, in, 0.25f, 0.25f, ns, false).z < 0.0f);
}

/// The blog's Möller–Trumbore: e1 = v1 - v0, e2 = v2 - v0, P = D x e2,
/// det = P . e1, T = O - v0, u = (T . P) / det, Q = T x e1, v = (D . Q) / det,
/// t = (e2 . Q) / det, each division a multiplication by 1 / det.
bool emulated_moller_trumbore(Vec3f o, Vec3f d, const Triangle& tri, float& t, float& u, float& v) {
  const Vec3f e1 = emu::sub(tri.v1, tri.v0), e2 = emu::sub(tri.v2, tri.v0);
  const Vec3f pv = emu::plain_cross(d, e2);
  const float det = emu::plain_dot(e1, pv);
  if (det == 0) return false;
  const float inv = emu::div(1, det);
  const Vec3f s = emu::sub(o, tri.v0);
  u = emu::mul(emu::plain_dot(s, pv), inv);
  if (u < 0 || u > 1) return false;
  const Vec3f q = emu::plain_cross(s, e1);
  v = emu::mul(emu::plain_dot(d, q), inv);
  if (v < 0 || emu::add(u, v) > 1) return false;
  t = emu::mul(emu::plain_dot(e2, q), inv);
  return t > 0;  // the blog closes [tmin, tmax]; vbsim's contract opens it (no t is exactly 0 here)
}

TEST_CASE("moller-trumbore is the blog's test, operation for operation", "[methods][tester]") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> c(-10, 10);
  int hits = 0;
  for (int i = 0; i < 4000; ++i) {
    const Triangle tri{{c(rng), c(rng), c(rng)}, {c(rng), c(rng), c(rng)}, {c(rng), c(rng), c(rng)}};
    Ray ray;
    ray.o = {c(rng), c(rng), c(rng)};
    const Vec3f target = 0.3f * tri.v0 + 0.3f * tri.v1 + 0.4f * tri.v2 + Vec3f{c(rng), c(rng), c(rng)} * 0.1f;
    ray.d = target - ray.o;
    float t = 0, u = 0, v = 0;
    const bool want = emulated_moller_trumbore(ray.o, ray.d, tri, t, u, v);
    Hit h;
    const bool got = MollerTrumboreTester(ray).intersect(tri, INFINITY, h);
    INFO("case " << i);
    REQUIRE(got == want);
    if (!got) continue;
    ++hits;
    REQUIRE(same_bits(h.t, t));
    REQUIRE(same_bits(h.u, u));
    REQUIRE(same_bits(h.v, v));
  }
  CHECK(hits > 1000);
}

}  // namespace
}  // namespace vbsim
