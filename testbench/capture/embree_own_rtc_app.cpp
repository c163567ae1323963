// A program with Embree's functions of its own, as a program linked to a
// static Embree has: no libembree3 is loaded and its calls never reach the
// capture shim. Its stand-ins answer every ray with a miss. For the capture
// test that such a program is refused with a reason, not captured as empty.
//
// Usage: embree_own_rtc_app
#include <embree3/rtcore.h>

#include <cstdio>

extern "C" {
RTCDevice rtcNewDevice(const char*) { static int device; return reinterpret_cast<RTCDevice>(&device); }
RTCScene rtcNewScene(RTCDevice) { static int scene; return reinterpret_cast<RTCScene>(&scene); }
void rtcCommitScene(RTCScene) {}
void rtcIntersect1(RTCScene, RTCIntersectContext*, RTCRayHit* rh) { rh->hit.geomID = RTC_INVALID_GEOMETRY_ID; }
}

int main() {
  RTCScene scene = rtcNewScene(rtcNewDevice(nullptr));
  rtcCommitScene(scene);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  int misses = 0;
  for (int i = 0; i < 100; ++i) {
    RTCRayHit rh{};
    rh.ray.dir_z = -1.0f;
    rh.ray.tfar = 10.0f;
    rtcIntersect1(scene, &context, &rh);
    misses += rh.hit.geomID == RTC_INVALID_GEOMETRY_ID;
  }
  std::printf("%d misses\n", misses);
  return 0;
}
