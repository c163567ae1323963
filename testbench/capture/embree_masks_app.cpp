// An Embree 3 application for the capture tests of ray masks: a ground square
// (Embree's default mask) and, above it, a second square hidden from some rays
// by masks. It traces a grid of camera rays down with ray masks 0x1, 0x3 and
// 0x6 in turn, and writes per ray its mask and the top-level geomID Embree hit
// (an instance's for a hit inside it), one line each,
// so the test can check what the trace holds and which rays it marks.
//
// Usage: embree_masks_app OUT.txt [MODE]
//   geometry (default): the upper square has rtcSetGeometryMask(0x2)
//   instance: it sits in a child scene (default mask), instanced with mask 0x2
//   both: instanced with mask 0x4, its geometry with mask 0x2 (a ray must share
//         a bit with each: one mask per triangle cannot hold that)
#include <embree3/rtcore.h>

#include <cstdio>
#include <cstring>

namespace {

const float kGround[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
const float kUpper[4][3] = {{-1, -1, 0.5f}, {1, -1, 0.5f}, {1, 1, 0.5f}, {-1, 1, 0.5f}};
const unsigned kSquare[2][3] = {{0, 1, 2}, {0, 2, 3}};

void attach_square(RTCDevice device, RTCScene scene, const float (*vertices)[3], unsigned mask) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices, 0, 12, 4);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, kSquare, 0, 12, 2);
  if (mask != 0xffffffffu) rtcSetGeometryMask(g, mask);
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
}

}  // namespace

/// Attaches the upper square to `scene` inside an instance of mask
/// `instance_mask` whose geometry has `geometry_mask`.
void attach_instanced_square(RTCDevice device, RTCScene scene, unsigned instance_mask, unsigned geometry_mask) {
  RTCScene child = rtcNewScene(device);
  attach_square(device, child, kUpper, geometry_mask);
  rtcCommitScene(child);
  RTCGeometry inst = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(inst, child);
  const float identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, identity);
  rtcSetGeometryMask(inst, instance_mask);
  rtcCommitGeometry(inst);
  rtcAttachGeometry(scene, inst);
  rtcReleaseGeometry(inst);
  rtcReleaseScene(child);
}

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) return std::fprintf(stderr, "usage: embree_masks_app OUT.txt [geometry|instance|both]\n"), 2;
  const char* mode = argc == 3 ? argv[2] : "geometry";
  FILE* out = std::fopen(argv[1], "w");
  if (!out) return std::perror(argv[1]), 1;
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  attach_square(device, scene, kGround, 0xffffffffu);
  if (std::strcmp(mode, "geometry") == 0) attach_square(device, scene, kUpper, 0x2u);
  else if (std::strcmp(mode, "instance") == 0) attach_instanced_square(device, scene, 0x2u, 0xffffffffu);
  else if (std::strcmp(mode, "both") == 0) attach_instanced_square(device, scene, 0x4u, 0x2u);
  else return std::fprintf(stderr, "embree_masks_app: unknown mode '%s'\n", mode), 2;
  rtcCommitScene(scene);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int i = 0; i < 64; ++i) {
    RTCRayHit rh{};
    rh.ray.org_x = -0.9f + 0.025f * static_cast<float>(i);
    rh.ray.org_y = 0.3f - 0.01f * static_cast<float>(i);
    rh.ray.org_z = 2.0f;
    rh.ray.dir_z = -1.0f;
    rh.ray.tfar = 100.0f;
    const unsigned masks[3] = {0x1u, 0x3u, 0x6u};
    rh.ray.mask = masks[i % 3];
    rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    // The top-level geometry hit: the instance's geomID for a hit inside it.
    const unsigned top = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? rh.hit.instID[0] : rh.hit.geomID;
    std::fprintf(out, "ray %u %u\n", rh.ray.mask, top);
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  std::fclose(out);
  return 0;
}
