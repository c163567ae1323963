// The scene and geometry functions the shim interposes: each calls the
// application's Embree with the same arguments, then tells the registry what
// happened. Nothing is changed on the way in or out.
#include "capture_output.h"
#include "real_embree.h"
#include "scene_registry.h"

using namespace vbsim::shim;

RTCScene rtcNewScene(RTCDevice device) {
  VBSIM_REAL(rtcNewScene);
  RTCScene scene = real(device);
  if (scene && capture_enabled()) {
    // Whether Embree skips geometry a ray's mask hides (a build option): a read-only query.
    static const auto property =
        reinterpret_cast<decltype(&::rtcGetDeviceProperty)>(embree_function("rtcGetDeviceProperty"));
    note_ray_masks(property(device, RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED) != 0);
    on_new_scene(scene);
  }
  return scene;
}

RTCGeometry rtcNewGeometry(RTCDevice device, enum RTCGeometryType type) {
  VBSIM_REAL(rtcNewGeometry);
  RTCGeometry geometry = real(device, type);
  if (geometry && capture_enabled()) on_new_geometry(geometry, type);
  return geometry;
}

unsigned int rtcAttachGeometry(RTCScene scene, RTCGeometry geometry) {
  VBSIM_REAL(rtcAttachGeometry);
  const unsigned int id = real(scene, geometry);
  if (id != RTC_INVALID_GEOMETRY_ID && capture_enabled()) on_attach(scene, geometry, id);
  return id;
}

void rtcAttachGeometryByID(RTCScene scene, RTCGeometry geometry, unsigned int geom_id) {
  VBSIM_REAL(rtcAttachGeometryByID);
  real(scene, geometry, geom_id);
  if (capture_enabled()) on_attach(scene, geometry, geom_id);
}

void rtcDetachGeometry(RTCScene scene, unsigned int geom_id) {
  VBSIM_REAL(rtcDetachGeometry);
  real(scene, geom_id);
  if (capture_enabled()) on_detach(scene, geom_id);
}

void rtcEnableGeometry(RTCGeometry geometry) {
  VBSIM_REAL(rtcEnableGeometry);
  real(geometry);
  if (capture_enabled()) on_enable(geometry, true);
}

void rtcDisableGeometry(RTCGeometry geometry) {
  VBSIM_REAL(rtcDisableGeometry);
  real(geometry);
  if (capture_enabled()) on_enable(geometry, false);
}

void rtcSetGeometryTimeStepCount(RTCGeometry geometry, unsigned int count) {
  VBSIM_REAL(rtcSetGeometryTimeStepCount);
  real(geometry, count);
  if (capture_enabled()) on_time_steps(geometry, count);
}

void rtcSetGeometryInstancedScene(RTCGeometry geometry, RTCScene scene) {
  VBSIM_REAL(rtcSetGeometryInstancedScene);
  real(geometry, scene);
  if (capture_enabled()) on_instanced_scene(geometry, scene);
}

void rtcSetGeometryTransform(RTCGeometry geometry, unsigned int time_step, enum RTCFormat format, const void* xfm) {
  VBSIM_REAL(rtcSetGeometryTransform);
  real(geometry, time_step, format, xfm);
  if (capture_enabled()) on_transform(geometry, time_step, format, xfm);
}

void rtcSetGeometryTransformQuaternion(RTCGeometry geometry, unsigned int time_step,
                                       const struct RTCQuaternionDecomposition* qd) {
  VBSIM_REAL(rtcSetGeometryTransformQuaternion);
  real(geometry, time_step, qd);
  if (capture_enabled()) on_quaternion_transform(geometry);
}

void rtcSetGeometryMask(RTCGeometry geometry, unsigned int mask) {
  VBSIM_REAL(rtcSetGeometryMask);
  real(geometry, mask);
  if (capture_enabled()) on_mask(geometry, mask);
}

void rtcSetGeometryBuffer(RTCGeometry geometry, enum RTCBufferType type, unsigned int slot, enum RTCFormat format,
                          RTCBuffer buffer, size_t offset, size_t stride, size_t count) {
  VBSIM_REAL(rtcSetGeometryBuffer);
  real(geometry, type, slot, format, buffer, offset, stride, count);
  if (capture_enabled()) on_buffer(geometry, type, slot, format, nullptr, buffer, offset, stride, count);
}

void rtcSetSharedGeometryBuffer(RTCGeometry geometry, enum RTCBufferType type, unsigned int slot,
                                enum RTCFormat format, const void* ptr, size_t offset, size_t stride, size_t count) {
  VBSIM_REAL(rtcSetSharedGeometryBuffer);
  real(geometry, type, slot, format, ptr, offset, stride, count);
  if (capture_enabled()) on_buffer(geometry, type, slot, format, ptr, nullptr, offset, stride, count);
}

void* rtcSetNewGeometryBuffer(RTCGeometry geometry, enum RTCBufferType type, unsigned int slot,
                              enum RTCFormat format, size_t stride, size_t count) {
  VBSIM_REAL(rtcSetNewGeometryBuffer);
  void* data = real(geometry, type, slot, format, stride, count);
  if (data && capture_enabled()) on_buffer(geometry, type, slot, format, data, nullptr, 0, stride, count);
  return data;
}

void rtcCommitScene(RTCScene scene) {
  VBSIM_REAL(rtcCommitScene);
  real(scene);
  if (capture_enabled()) on_commit(scene);
}

void rtcJoinCommitScene(RTCScene scene) {
  VBSIM_REAL(rtcJoinCommitScene);
  real(scene);
  if (capture_enabled()) on_commit(scene);  // every joining thread: unchanged snapshots are skipped
}
