// What the shim knows of the application's Embree scenes: each geometry's
// type, buffers (shared, new or RTCBuffer) and state, each scene's attached
// geometries, and the snapshot of a scene's triangles written at every commit
// that changed them. Thread-safe; ray calls read only scene_stamp().
#pragma once
#include <embree3/rtcore.h>

#include <cstddef>
#include <cstdint>

namespace vbsim::shim {

/// Which snapshot a ray was traced against.
struct SceneStamp {
  uint32_t scene = 0xffffffffu;  ///< ordinal in rtcNewScene order
  uint32_t commit = 0;           ///< snapshot number (0: none yet)
};

void on_new_scene(RTCScene scene);
void on_new_geometry(RTCGeometry geometry, RTCGeometryType type);
void on_attach(RTCScene scene, RTCGeometry geometry, unsigned geom_id);
void on_detach(RTCScene scene, unsigned geom_id);
void on_enable(RTCGeometry geometry, bool enabled);
void on_time_steps(RTCGeometry geometry, unsigned count);
void on_instanced_scene(RTCGeometry geometry, RTCScene scene);
/// rtcSetGeometryTransform: time step `step` in `format` (any of Embree's layouts).
void on_transform(RTCGeometry geometry, unsigned step, RTCFormat format, const void* xfm);
/// rtcSetGeometryTransformQuaternion: a transform the capture does not flatten.
void on_quaternion_transform(RTCGeometry geometry);
/// A filter function (RawGeometryFilter `which`) set on the geometry, or cleared.
void on_filter(RTCGeometry geometry, uint32_t which, bool set);
/// rtcSetGeometryMask: rays whose mask shares no bit with it do not see the geometry.
void on_mask(RTCGeometry geometry, uint32_t mask);
/// A buffer bound to (type, slot): data at `ptr` + `offset` (shared and new buffers), else in `buffer` at `offset`.
void on_buffer(RTCGeometry geometry, RTCBufferType type, unsigned slot, RTCFormat format, const void* ptr,
               RTCBuffer buffer, std::size_t offset, std::size_t stride, std::size_t count);
/// After a (join) commit: writes a snapshot when the triangles differ from the last one.
void on_commit(RTCScene scene);

/// The scene's current stamp; cheap when the calling thread asked about the same scene before.
SceneStamp scene_stamp(RTCScene scene);

}  // namespace vbsim::shim
