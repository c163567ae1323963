// A program with Embree's functions of its own, as a program linked to a
// static Embree has: no libembree3 is loaded and its calls never reach the
// capture shim. Its stand-ins answer every ray with a miss. For the capture
// test that such a program is refused with a reason, not captured as empty.
// Like Embree's own code, it holds a polymorphic embree::Device, whose type
// name stays in the program when it is stripped (the build makes a stripped
// copy, vbsim_capture_own_rtc_app_stripped, for the check that reads no symbols).
//
// Usage: embree_own_rtc_app
#include <embree3/rtcore.h>

#include <cstdio>
#include <typeinfo>

namespace embree {
/// A stand-in of Embree's device class: polymorphic, so its type name is in the program.
struct Device {
  virtual ~Device() = default;
  virtual int threads() const { return 1; }
};
}  // namespace embree

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
  const embree::Device device;
  std::printf("%d misses (device %s, %d thread)\n", misses, typeid(device).name(), device.threads());
  return 0;
}
