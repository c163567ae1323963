// Quads in a capture: the snapshot reader splits each quad as Embree does,
// (v0, v1, v3) and (v2, v3, v1), and maps Embree's quad hit (primID, u, v)
// to the trace triangle and its barycentrics. Held against Embree itself:
// rays traced at a quad mesh by Embree, whose hits must land, through the
// mapping, on the point Embree found and on the triangle that Embree finds
// when given the two triangles instead of the quad.
#include <catch2/catch.hpp>

#include <embree3/rtcore.h>

#include <cmath>
#include <cstring>

#include "capture/captured_scene.h"
#include "scene/embree_reference.h"
#include "scene/scene.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::capture;
using namespace vbsim::test;

namespace {

// Two quads, non-square and not axis-aligned, in the plane z = 0.25 x + 1.
const float kVertices[6][3] = {{0, 0, 1}, {4, -1, 2}, {5, 3, 2.25f}, {-1, 2, 0.75f}, {9, 0, 3.25f}, {8, 4, 3}};
const uint32_t kQuads[2][4] = {{0, 1, 2, 3}, {1, 4, 5, 2}};

/// A snapshot holding the two quads as geometry 3 (as the shim writes it: uint4 indices).
std::string quad_snapshot() {
  std::string b(kRawSceneMagic, 8);
  const uint32_t head[4] = {0, 1, 1, 0};
  b.append(reinterpret_cast<const char*>(head), sizeof head);
  const RawGeometry quads{3, RTC_GEOMETRY_TYPE_QUAD, 0, 6, 2, 0};
  b.append(reinterpret_cast<const char*>(&quads), sizeof quads);
  b.append(reinterpret_cast<const char*>(kVertices), sizeof kVertices);
  b.append(reinterpret_cast<const char*>(kQuads), sizeof kQuads);
  return b;
}

struct EmbreeQuads {
  RTCDevice device = rtcNewDevice("threads=1");
  RTCScene scene = rtcNewScene(device);
  EmbreeQuads() {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, kVertices, 0, 12, 6);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, kQuads, 0, 16, 2);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
  }
  ~EmbreeQuads() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

}  // namespace

TEST_CASE("captured quads: split as Embree splits them, Embree's quad hits mapped to the triangles",
          "[capture]") {
  TempDir dir("captured-quads");
  write_file(dir.file("q.bin"), quad_snapshot());
  const CapturedScene s = CapturedScene::read(dir.file("q.bin"));
  REQUIRE(s.triangles().size() == 4);
  CHECK(s.geometries()[0].triangles == 4);
  const Vec3f v0{0, 0, 1}, v1{4, -1, 2}, v2{5, 3, 2.25f}, v3{-1, 2, 0.75f};
  CHECK((s.triangles()[0].v0 == v0 && s.triangles()[0].v1 == v1 && s.triangles()[0].v2 == v3));
  CHECK((s.triangles()[1].v0 == v2 && s.triangles()[1].v1 == v3 && s.triangles()[1].v2 == v1));
  CHECK(s.triangle_hit(3, 1, 0.5f, 0.75f).triangle == 3);
  CHECK(s.triangle_hit(3, 2, 0.1f, 0.1f).triangle == -1);  // no third quad

  const EmbreeQuads quads;
  const EmbreeReference split(make_scene(s.triangles()));
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  int hits = 0, second = 0, same_triangle = 0, diagonal = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 48; ++j) {
      RTCRayHit rh{};
      rh.ray.org_x = -1.5f + 11.0f * i / 64, rh.ray.org_y = -1.5f + 6.0f * j / 48, rh.ray.org_z = 10;
      rh.ray.dir_x = 0.01f * (i % 7), rh.ray.dir_y = -0.02f * (j % 5), rh.ray.dir_z = -1;
      rh.ray.tfar = INFINITY;
      rh.ray.mask = 0xffffffffu;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(quads.scene, &ctx, &rh);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      ++hits;
      INFO("ray " << i << "," << j << ": quad " << rh.hit.primID << " u " << rh.hit.u << " v " << rh.hit.v);
      const TriangleHit h = s.triangle_hit(3, rh.hit.primID, rh.hit.u, rh.hit.v);
      REQUIRE(h.triangle >= 0);
      CHECK(h.triangle / 2 == rh.hit.primID);
      second += h.triangle % 2;
      // The triangle's barycentric point is Embree's hit point.
      const Triangle& t = s.triangles()[static_cast<std::size_t>(h.triangle)];
      const double w = 1.0 - h.u - h.v;
      const double p[3] = {w * t.v0.x + h.u * t.v1.x + h.v * t.v2.x, w * t.v0.y + h.u * t.v1.y + h.v * t.v2.y,
                           w * t.v0.z + h.u * t.v1.z + h.v * t.v2.z};
      const double q[3] = {rh.ray.org_x + double(rh.ray.tfar) * rh.ray.dir_x,
                           rh.ray.org_y + double(rh.ray.tfar) * rh.ray.dir_y,
                           rh.ray.org_z + double(rh.ray.tfar) * rh.ray.dir_z};
      for (int k = 0; k < 3; ++k) CHECK(std::fabs(p[k] - q[k]) <= 1e-5 * (1.0 + std::fabs(q[k])));
      CHECK(h.u >= -1e-6f);
      CHECK(h.v >= -1e-6f);
      CHECK(h.u + h.v <= 1.0f + 1e-6f);
      // Embree, given the two triangles, names the same one (but on the diagonal, which both hold).
      int32_t prim;
      float tt, u, v;
      REQUIRE(split.intersect({rh.ray.org_x, rh.ray.org_y, rh.ray.org_z}, {rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z},
                              0.0f, INFINITY, prim, tt, u, v));
      if (std::fabs(rh.hit.u + rh.hit.v - 1.0f) < 1e-5f) ++diagonal;
      else CHECK(prim == h.triangle);
      same_triangle += prim == h.triangle;
    }
  CHECK(hits > 1000);
  CHECK(second > hits / 4);  // both halves of the quads are exercised
  CHECK(same_triangle + diagonal >= hits);
}
