// An Embree 3 application for the capture tests of instances: a child scene
// (a unit square as two triangles, and a quad) instanced four times into a
// top scene that also holds a ground triangle, each instance's transform set
// with rtcSetGeometryTransform in another of Embree's formats (3x4 row-major,
// 3x4 column-major, 4x4 column-major, 4x4 row-major). It traces a grid of
// camera rays and a shadow ray from every hit, and writes, per instance, its
// geomID, the format and the transform it meant (row-major 3x4, hex floats),
// so the tests can check the flattened triangles against it.
//
// Usage: embree_instances_app OUT.txt
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdio>

namespace {

const float kSquare[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const unsigned kSquareTriangles[2][3] = {{0, 1, 2}, {0, 2, 3}};
const float kQuad[4][3] = {{0, 0, 0.5f}, {0.5f, 0, 0.5f}, {0.5f, 0.5f, 0.5f}, {0, 0.5f, 0.5f}};
const unsigned kQuadIndex[4] = {0, 1, 2, 3};
const float kGround[3][3] = {{-10, -10, -1}, {30, -10, -1}, {-10, 30, -1}};
const unsigned kGroundIndex[3] = {0, 1, 2};

/// Attaches a triangle (or quad) mesh over shared buffers to `scene`.
void attach_mesh(RTCDevice device, RTCScene scene, bool quads, const void* vertices, unsigned nv,
                 const void* indices, unsigned n) {
  RTCGeometry g = rtcNewGeometry(device, quads ? RTC_GEOMETRY_TYPE_QUAD : RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices, 0, 12, nv);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, quads ? RTC_FORMAT_UINT4 : RTC_FORMAT_UINT3, indices, 0,
                             quads ? 16 : 12, n);
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
}

RTCScene child_scene(RTCDevice device) {
  RTCScene s = rtcNewScene(device);
  attach_mesh(device, s, false, kSquare, 4, kSquareTriangles, 2);
  attach_mesh(device, s, true, kQuad, 4, kQuadIndex, 1);
  rtcCommitScene(s);
  return s;
}

/// Instance k's transform, row-major 3x4: a rotation about z, a scale, a shift.
void transform_of(int k, float m[12]) {
  const float a = 0.3f + 0.4f * k, s = 1.5f + 0.25f * k;
  const float c = std::cos(a) * s, n = std::sin(a) * s;
  const float row[12] = {c, -n, 0, 4.0f * k + 0.1f, n, c, 0, 0.2f * k, 0, 0, 0.75f, 0.1f * k};
  for (int i = 0; i < 12; ++i) m[i] = row[i];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return std::fprintf(stderr, "usage: embree_instances_app OUT.txt\n"), 2;
  FILE* out = std::fopen(argv[1], "w");
  if (!out) return std::perror(argv[1]), 1;
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene child = child_scene(device);
  RTCScene top = rtcNewScene(device);
  attach_mesh(device, top, false, kGround, 3, kGroundIndex, 1);
  const RTCFormat formats[4] = {RTC_FORMAT_FLOAT3X4_ROW_MAJOR, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR,
                                RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, RTC_FORMAT_FLOAT4X4_ROW_MAJOR};
  const char* names[4] = {"float3x4_row_major", "float3x4_column_major", "float4x4_column_major",
                          "float4x4_row_major"};
  for (int k = 0; k < 4; ++k) {
    float m[12], buf[16] = {};
    transform_of(k, m);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) {
        if (k == 0 || k == 3) buf[r * 4 + c] = m[r * 4 + c];  // row-major, 3x4 or the top of 4x4
        if (k == 1) buf[c * 3 + r] = m[r * 4 + c];
        if (k == 2) buf[c * 4 + r] = m[r * 4 + c];
      }
    if (k == 2) buf[15] = 1;
    if (k == 3) buf[15] = 1;
    RTCGeometry inst = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, child);
    rtcSetGeometryTransform(inst, 0, formats[k], buf);
    const bool accepted = rtcGetDeviceError(device) == RTC_ERROR_NONE;
    rtcCommitGeometry(inst);
    if (accepted) {
      const unsigned id = rtcAttachGeometry(top, inst);
      std::fprintf(out, "instance %u %s", id, names[k]);
      for (float x : m) std::fprintf(out, " %a", x);
      std::fprintf(out, "\n");
    } else {
      std::fprintf(out, "unsupported %s\n", names[k]);
    }
    rtcReleaseGeometry(inst);
  }
  rtcCommitScene(top);

  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  int hits = 0;
  for (int i = 0; i < 96; ++i)
    for (int j = 0; j < 48; ++j) {
      RTCRayHit rh{};
      rh.ray.org_x = -2.0f + 18.0f * i / 96, rh.ray.org_y = -1.5f + 5.0f * j / 48, rh.ray.org_z = 10;
      rh.ray.dir_x = 0.013f * (i % 5), rh.ray.dir_y = 0.011f * (j % 3), rh.ray.dir_z = -1;
      rh.ray.tfar = INFINITY;
      rh.ray.mask = 0xffffffffu;
      rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(top, &ctx, &rh);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      ++hits;
      RTCRay shadow{};
      shadow.org_x = rh.ray.org_x + rh.ray.tfar * rh.ray.dir_x;
      shadow.org_y = rh.ray.org_y + rh.ray.tfar * rh.ray.dir_y;
      shadow.org_z = rh.ray.org_z + rh.ray.tfar * rh.ray.dir_z;
      shadow.dir_x = 5 - shadow.org_x, shadow.dir_y = 1 - shadow.org_y, shadow.dir_z = 20 - shadow.org_z;
      shadow.tnear = 1e-4f, shadow.tfar = 1, shadow.mask = 0xffffffffu;
      rtcOccluded1(top, &ctx, &shadow);
    }
  std::fprintf(out, "hits %d\n", hits);
  std::fclose(out);
  rtcReleaseScene(top);
  rtcReleaseScene(child);
  rtcReleaseDevice(device);
  return 0;
}
