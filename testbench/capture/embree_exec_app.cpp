// An Embree 3 application for the capture test of exec(): it traces a number
// of camera rays at a square, then replaces itself (same pid) with a run of
// itself that traces the next number, and so on, each image through another
// exec function (execvp while three or more counts are left, then execv, then
// execl), writing to OUT.txt one line
// "image PID RAYS" per image, so the test can hold every image's rays against
// the capture's account.
//
// Usage: embree_exec_app OUT.txt RAYS [RAYS...]
#include <embree3/rtcore.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

const float kSquare[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
const unsigned kIndices[2][3] = {{0, 1, 2}, {0, 2, 3}};

void trace(long rays) {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, kSquare, 0, 12, 4);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, kIndices, 0, 12, 2);
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (long i = 0; i < rays; ++i) {
    RTCRayHit rh{};
    rh.ray.org_x = -0.9f + 1.8f * static_cast<float>(i % 97) / 97.0f;
    rh.ray.org_y = -0.9f + 1.8f * static_cast<float>(i / 97 % 89) / 89.0f;
    rh.ray.org_z = 2.0f + 0.001f * static_cast<float>(i / (97 * 89));
    rh.ray.dir_z = -1.0f;
    rh.ray.tfar = 100.0f;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return std::fprintf(stderr, "usage: embree_exec_app OUT.txt RAYS [RAYS...]\n"), 2;
  const long rays = std::atol(argv[2]);
  trace(rays);
  FILE* out = std::fopen(argv[1], "a");
  if (!out) return std::perror(argv[1]), 1;
  std::fprintf(out, "image %ld %ld\n", static_cast<long>(::getpid()), rays);
  std::fclose(out);
  if (argc == 3) return 0;
  // The next image: the same program with the rest of the counts, the records
  // of this one still in the shim's buffers (no exit handler runs on exec).
  std::vector<char*> next{argv[0], argv[1]};
  for (int i = 3; i < argc; ++i) next.push_back(argv[i]);
  next.push_back(nullptr);
  switch (argc - 3) {  // the counts left after this image's
    case 1: ::execl("/proc/self/exe", argv[0], argv[1], argv[3], static_cast<char*>(nullptr)); break;
    case 2: ::execv("/proc/self/exe", next.data()); break;
    default: ::execvp(argv[0], next.data()); break;
  }
  std::perror("exec");
  return 1;
}
