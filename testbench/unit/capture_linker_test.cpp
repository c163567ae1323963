// The capture's parent linking and kind rules on hand-made Embree records
// over one triangle, and the scene snapshot reader's numbering and errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "capture/captured_scene.h"
#include "capture/parent_linker.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::capture;
using namespace vbsim::test;

namespace {

RawRay ray(RawOp op, Vec3f o, Vec3f d) {
  RawRay r{};
  r.op = static_cast<uint16_t>(op);
  r.org[0] = o.x, r.org[1] = o.y, r.org[2] = o.z;
  r.dir[0] = d.x, r.dir[1] = d.y, r.dir[2] = d.z;
  r.tfar = INFINITY;
  r.hit_t = INFINITY;
  r.geom = r.prim = r.inst = kInvalidId;
  return r;
}

/// A snapshot file: geometry 4 (the floor z = 0 as two triangles) and geometry 1, a quad mesh.
std::string snapshot_bytes(uint32_t bad_index = 1) {
  std::string b(kRawSceneMagic, 8);
  const uint32_t head[4] = {0, 1, 2, 0};
  b.append(reinterpret_cast<const char*>(head), sizeof head);
  const RawGeometry quad{1, 1, static_cast<uint32_t>(RawGeometryStatus::NotTriangles), 0, 0, 0};
  b.append(reinterpret_cast<const char*>(&quad), sizeof quad);
  const RawGeometry floor{4, 0, 0, 4, 2, 0};
  b.append(reinterpret_cast<const char*>(&floor), sizeof floor);
  const float v[12] = {-10, -10, 0, 10, -10, 0, 10, 10, 0, -10, 10, 0};
  b.append(reinterpret_cast<const char*>(v), sizeof v);
  const uint32_t idx[6] = {0, bad_index, 2, 0, 2, 3};
  b.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return b;
}

}  // namespace

TEST_CASE("captured scene: triangle ids follow geomID order, primitives in order", "[capture]") {
  TempDir dir("captured-scene");
  write_file(dir.file("s.bin"), snapshot_bytes());
  const CapturedScene s = CapturedScene::read(dir.file("s.bin"));
  REQUIRE(s.triangles().size() == 2);
  CHECK(s.triangle_hit(4, 0, 0.25f, 0.25f).triangle == 0);
  CHECK(s.triangle_hit(4, 1, 0.25f, 0.25f).triangle == 1);
  CHECK(s.triangle_hit(4, 2, 0.25f, 0.25f).triangle == -1);  // out of range
  CHECK(s.triangle_hit(1, 0, 0.25f, 0.25f).triangle == -1);  // geometry 1 is not captured (its status)
  CHECK(s.triangle_hit(9, 0, 0.25f, 0.25f).triangle == -1);
  CHECK(s.triangles()[1].v2 == Vec3f{-10, 10, 0});
  CHECK(s.geometries()[0].status == RawGeometryStatus::NotTriangles);

  write_file(dir.file("bad.bin"), snapshot_bytes(4));
  CHECK_THROWS_WITH(CapturedScene::read(dir.file("bad.bin")),
                    Catch::Contains("bad.bin") && Catch::Contains("names vertex 4"));
  const std::string whole = snapshot_bytes();
  write_file(dir.file("short.bin"), whole.substr(0, whole.size() - 5));
  CHECK_THROWS_WITH(CapturedScene::read(dir.file("short.bin")), Catch::Contains("truncated"));
}

TEST_CASE("parent linker: hit point, normal offset, kinds, and what stays unlinked", "[capture]") {
  TempDir dir("capture-linker");
  write_file(dir.file("s.bin"), snapshot_bytes());
  const CapturedScene scene = CapturedScene::read(dir.file("s.bin"));
  const ParentLinker linker(scene, LinkRules{});
  // The camera ray from (1, 2, 5) along (0.6, 0, -0.8) meets the floor (z = 0) at t = 6.25, at (4.75, 2, 0).
  RawRay cam = ray(RawOp::Intersect, {1, 2, 5}, {0.6f, 0, -0.8f});
  cam.hit_t = 6.25f, cam.geom = 4, cam.prim = 0;
  const Vec3f p{1 + 6.25f * 0.6f, 2, 5 + 6.25f * -0.8f};
  REQUIRE(p.z == 0.0f);
  std::vector<RawRay> rays = {
      cam,
      ray(RawOp::Occluded, p, {0, 0, 1}),                            // 1 shadow from the hit point
      ray(RawOp::Intersect, {p.x, p.y, 1e-4f}, {0.6f, 0, 0.8f}),     // 2 mirror, offset along the normal
      ray(RawOp::Intersect, {p.x, p.y, -1e-4f}, {0.6f, 0, -0.8f}),   // 3 continues below: refract
      ray(RawOp::Intersect, p, {0.1f, 0.2f, 0.9f}),                  // 4 diffuse
      ray(RawOp::Intersect, {p.x + 1e-3f, p.y, 0}, {0, 0, 1}),       // 5 sideways of the hit: unlinked
      ray(RawOp::Intersect, {p.x, p.y, 0.5f}, {0, 0, 1}),            // 6 too far along the normal: unlinked
      ray(RawOp::Occluded, {p.x, p.y, 0}, {0, 0, 1}),                // 7 not eligible (another scene)
  };
  std::vector<bool> eligible(rays.size(), true);
  eligible[7] = false;
  LinkCounts counts;
  const std::vector<RayLink> links = linker.link(rays.data(), rays.size(), eligible, counts);
  CHECK(links[0].parent == -1);
  CHECK(links[0].kind == RayKind::Primary);
  CHECK((links[1].parent == 0 && links[1].kind == RayKind::Shadow && links[1].tier == LinkTier::AtHitPoint));
  CHECK((links[2].parent == 0 && links[2].kind == RayKind::Reflect && links[2].tier == LinkTier::NormalOffset));
  CHECK(links[2].offset == Approx(1e-4 / 6.25 / 0.8).epsilon(1e-3));  // offset / max(|P|, |t d|) = 1e-4 / 5
  CHECK((links[3].parent == 0 && links[3].kind == RayKind::Refract));
  CHECK((links[4].parent == 0 && links[4].kind == RayKind::Diffuse && links[4].tier == LinkTier::AtHitPoint));
  CHECK(links[5].parent == -1);
  CHECK(links[6].parent == -1);
  CHECK(links[7].parent == -1);
  CHECK(counts.at_hit_point == 2);
  CHECK(counts.normal_offset == 2);
  CHECK(counts.unlinked_intersect == 3);
  CHECK(counts.unlinked_occluded == 0);
  CHECK(counts.by_kind[static_cast<int>(RayKind::Reflect)] == 1);

  // With no normal offset allowed, only the exact hit points link.
  LinkRules exact;
  exact.normal_offset = 0;
  LinkCounts c2;
  const auto strict = ParentLinker(scene, exact).link(rays.data(), rays.size(), eligible, c2);
  CHECK(strict[2].parent == -1);
  CHECK(strict[4].parent == 0);
  // The tolerance is in ulps of the largest of |P| (4.75 here), |t d| (6.25) and the triangle's
  // vertex coordinates (10: ulp 2^-20, twice the ulp of 6.25): with 4 ulps, a ray 8 ulps of p.x
  // (4.75: 2^-21) off links, 10 off does not.
  exact.ulps = 4;
  RawRay near = rays[4];
  near.org[0] = p.x;
  for (int k = 0; k < 8; ++k) near.org[0] = std::nextafter(near.org[0], 10.0f);
  RayLink l;
  CHECK(ParentLinker(scene, exact).origin_matches(cam, scene.triangles()[0], near, l));
  for (int k = 0; k < 2; ++k) near.org[0] = std::nextafter(near.org[0], 10.0f);
  CHECK_FALSE(ParentLinker(scene, exact).origin_matches(cam, scene.triangles()[0], near, l));
}

TEST_CASE("parent linker: finite-tfar intersect children are shadow rays, and a rejected primitive links further",
          "[capture]") {
  TempDir dir("capture-linker-rejected");
  write_file(dir.file("s.bin"), snapshot_bytes());
  const CapturedScene scene = CapturedScene::read(dir.file("s.bin"));
  RawRay cam = ray(RawOp::Intersect, {1, 2, 5}, {0.6f, 0, -0.8f});
  cam.hit_t = 6.25f, cam.geom = 4, cam.prim = 0;
  const Vec3f p{4.75f, 2, 0};
  RawRay toward_light = ray(RawOp::Intersect, p, {0, 0.6f, 0.8f});
  toward_light.tfar = 7.5f;  // a visibility query toward a point, as Cycles casts shadow rays
  RawRay unbounded = ray(RawOp::Intersect, p, {0.1f, 0.2f, 0.9f});
  unbounded.tfar = 3.40282347e38f;  // FLT_MAX: an ordinary bounce
  // 40 ulps of 10 off the hit point: beyond 16 ulps, within 64 of the primitive its filter rejected.
  RawRay far = ray(RawOp::Intersect, {p.x + 40 * 9.5367431640625e-7f, p.y, 0}, {0.1f, 0.2f, 0.9f});
  RawRay far_rejected = far;
  far_rejected.flags = kRawFilterRejected;
  far_rejected.rejected_geom = 4, far_rejected.rejected_prim = 0, far_rejected.rejected_inst = kInvalidId;
  RawRay far_other = far_rejected;
  far_other.rejected_prim = 1;  // the filter rejected another primitive: no hint
  const std::vector<RawRay> rays = {cam, toward_light, unbounded, far, far_rejected, far_other};
  LinkCounts counts;
  const auto links = ParentLinker(scene, LinkRules{}).link(rays.data(), rays.size(),
                                                           std::vector<bool>(rays.size(), true), counts);
  CHECK((links[1].parent == 0 && links[1].kind == RayKind::Shadow));
  CHECK((links[2].parent == 0 && links[2].kind == RayKind::Diffuse));
  CHECK(links[3].parent == -1);
  CHECK((links[4].parent == 0 && links[4].tier == LinkTier::RejectedPrimitive));
  CHECK(links[5].parent == -1);
  CHECK(counts.rejected_primitive == 1);
}
