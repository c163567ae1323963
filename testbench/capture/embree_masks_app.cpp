// An Embree 3 application for the capture test of geometry masks: a ground
// square (Embree's default mask) and, above it, a second square with
// rtcSetGeometryMask(0x2). It traces a grid of camera rays down, alternately
// with ray mask 0x1 (the upper square is hidden from them: Embree answers the
// ground) and 0x3 (they see both: Embree answers the upper square), and writes
// per ray its mask and Embree's geomID, one line each, so the test can check
// which rays the trace marks.
//
// Usage: embree_masks_app OUT.txt
#include <embree3/rtcore.h>

#include <cstdio>

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

int main(int argc, char** argv) {
  if (argc != 2) return std::fprintf(stderr, "usage: embree_masks_app OUT.txt\n"), 2;
  FILE* out = std::fopen(argv[1], "w");
  if (!out) return std::perror(argv[1]), 1;
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  attach_square(device, scene, kGround, 0xffffffffu);
  attach_square(device, scene, kUpper, 0x2u);
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
    rh.ray.mask = i % 2 == 0 ? 0x1u : 0x3u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    std::fprintf(out, "ray %u %u\n", rh.ray.mask, rh.hit.geomID);
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  std::fclose(out);
  return 0;
}
