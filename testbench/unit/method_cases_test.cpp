// Each self-intersection method's documented behaviour on hand-built scenes
// (Ray Tracing Gems ch. 6.2.2 failure cases, the patent's refraction case),
// scored against the exact oracle.
#include <catch2/catch.hpp>

#include <cmath>

#include "exact/oracle.h"
#include "replay/functional_replayer.h"

using namespace vbsim;

namespace {

/// Replays `tr` (expect filled in by the exact oracle) under `method`.
RayOutcome replay_with(const Scene& scene, TraceRay tr, const std::string& method,
                       void (*tune)(ReplayOptions&) = nullptr) {
  const Bvh bvh = build_bvh(scene);
  const OracleAnswer ans = Oracle(scene, bvh).answer(intended_ray(tr, scene, nullptr));
  tr.has_expect = true;
  tr.expect_prim = ans.prim;
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method(method, opt.method, err));
  opt.method.avoidance.eps_mode = EpsilonMode::Fixed;
  opt.method.avoidance.eps = 1e-4f;
  if (tune) tune(opt);
  FunctionalReplayer replayer(scene, bvh, opt);
  return replayer.replay(tr);
}

/// Child of a hit on triangle `prim`: origin `o` (as a renderer rounded it), direction d.
TraceRay child(Vec3f o, Vec3f d, int32_t prim, RayKind kind = RayKind::Reflect) {
  TraceRay tr;
  tr.id = 1;
  tr.parent = 0;
  tr.kind = kind;
  tr.o = o;
  tr.d = d;
  tr.parent_prim = prim;
  return tr;
}

// A flat square in z = 0 made of two triangles sharing the edge x + y = 1,
// both with Ng = (0, 0, +1).
Scene flat_square() {
  return make_scene({Triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, Triangle{{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}});
}

}  // namespace

TEST_CASE("tmin fails on a grazing child ray, validity-bit with vote rejects the re-hit", "[methods]") {
  const Scene scene = flat_square();
  // The hit point landed 1e-6 below the plane; the child leaves at slope 1e-3 toward
  // +x: it meets its own plane again 1e-3 further on, far beyond tmin = 1e-4.
  const TraceRay tr = child({0.2f, 0.2f, -1e-6f}, {1, 0, 1e-3f}, 0);
  const RayOutcome none = replay_with(scene, tr, "none");
  CHECK(none.hit.prim == 0);
  CHECK(none.verdict == Verdict::SelfHit);
  const RayOutcome tmin = replay_with(scene, tr, "tmin");
  CHECK(tmin.hit.prim == 0);
  CHECK(tmin.verdict == Verdict::SelfHit);
  const RayOutcome vote = replay_with(scene, tr, "validity-bit", [](ReplayOptions& o) {
    o.method.avoidance.policy = AvoidancePolicy::Vote;
  });
  CHECK(vote.hit.prim == -1);
  CHECK(vote.rejected == 1);
  CHECK(vote.verdict == Verdict::Correct);
}

TEST_CASE("primid fails next to a shared edge of a flat mesh, validity-bit rejects it", "[methods]") {
  const Scene scene = flat_square();
  // Hit on triangle 0 right next to the shared edge, rounded 1e-7 below; the child
  // grazes across the edge and re-hits the plane inside triangle 1.
  const TraceRay tr = child({0.4999f, 0.5f, -1e-7f}, {1, 1, 1e-4f}, 0);
  const RayOutcome primid = replay_with(scene, tr, "primid");
  CHECK(primid.hit.prim == 1);
  CHECK(primid.verdict == Verdict::SelfHit);
  const RayOutcome vb = replay_with(scene, tr, "validity-bit", [](ReplayOptions& o) {
    o.method.avoidance.test_ray = false;  // the normal test alone
  });
  CHECK(vb.hit.prim == -1);
  CHECK(vb.verdict == Verdict::Correct);
}

TEST_CASE("offset-adaptive holds far from the origin where a fixed normal offset does not",
          "[methods]") {
  // Floor at z = 2^20 (Ng = +z); a hit point rounded one ulp (2^-4 there) below it.
  const float z = 1048576.0f;
  const Scene scene = make_scene({Triangle{{0, 0, z}, {4096, 0, z}, {0, 4096, z}}});
  const TraceRay tr = child({100.0f, 100.0f, std::nextafter(z, 0.0f)}, {0.3f, 0.2f, 1.0f}, 0);
  const RayOutcome fixed = replay_with(scene, tr, "offset-normal");  // 1e-4 is below one ulp
  CHECK(fixed.hit.prim == 0);
  CHECK(fixed.verdict == Verdict::SelfHit);
  const RayOutcome adaptive = replay_with(scene, tr, "offset-adaptive");
  CHECK(adaptive.hit.prim == -1);
  CHECK(adaptive.verdict == Verdict::Correct);
}

TEST_CASE("validity-bit keeps a refraction ray's exit hit and rejects its entry re-hit", "[methods]") {
  // Slab of glass between z = 0 (top face, Ng = +z) and z = -1 (bottom face, Ng = -z).
  const Scene scene = make_scene({Triangle{{-5, -5, 0}, {5, -5, 0}, {0, 5, 0}},
                                  Triangle{{-5, -5, -1}, {0, 5, -1}, {5, -5, -1}}});
  REQUIRE(geometric_normal(scene.triangles[0]).z > 0);
  REQUIRE(geometric_normal(scene.triangles[1]).z < 0);
  // The refraction child enters through the top face; its origin was rounded 1e-7
  // above the face, so it re-hits the face it is entering through.
  const TraceRay tr = child({0.1f, 0.1f, 1e-7f}, {0.2f, 0.1f, -1.0f}, 0, RayKind::Refract);
  const RayOutcome none = replay_with(scene, tr, "none");
  CHECK(none.hit.prim == 0);
  CHECK(none.verdict == Verdict::SelfHit);
  const RayOutcome vb = replay_with(scene, tr, "validity-bit");
  // sign 1 (entering, against Ng); top face met from the front (bit 1): suspect,
  // rejected; bottom face met from inside along its Ng... its front bit is 0: kept.
  CHECK(vb.rejected == 1);
  CHECK(vb.hit.prim == 1);
  CHECK(vb.hit.front == 0);
  CHECK(vb.verdict == Verdict::Correct);
}

TEST_CASE("reverse-shadow ignores the parent triangle that a forward shadow ray re-hits", "[methods]") {
  const Scene scene = flat_square();
  // Shadow ray to a light above, from 1e-7 below the floor: acne without a method.
  TraceRay tr = child({0.2f, 0.2f, -1e-7f}, {0.1f, 0.1f, 5.0f}, 0, RayKind::Shadow);
  tr.tmax = 1.0f;
  CHECK(replay_with(scene, tr, "none").verdict == Verdict::SelfHit);
  const RayOutcome rev = replay_with(scene, tr, "reverse-shadow");
  CHECK(rev.reversed);
  CHECK(rev.answer == -1);
  CHECK(rev.verdict == Verdict::Correct);
}
