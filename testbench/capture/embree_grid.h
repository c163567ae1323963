// The scene and rays of the capture tests of how Embree is loaded: two
// triangles of a tilted square and, above it, a small square; a 16 x 16 grid
// of camera rays down, and from each hit a shadow ray up. Written once over
// a table of Embree's functions, so that a program linked to Embree and one
// that looks the functions up with dlsym trace exactly the same rays. Per ray
// one line "geomID primID t" (shadow rays: "occluded 0/1") goes to `out`.
#pragma once
#include <embree3/rtcore.h>

#include <cstdio>
#include <initializer_list>

namespace vbsim::test {

/// The Embree 3 functions the grid calls.
struct EmbreeGridApi {
  decltype(&rtcNewDevice) new_device;
  decltype(&rtcNewScene) new_scene;
  decltype(&rtcNewGeometry) new_geometry;
  decltype(&rtcSetSharedGeometryBuffer) set_shared_buffer;
  decltype(&rtcCommitGeometry) commit_geometry;
  decltype(&rtcAttachGeometry) attach_geometry;
  decltype(&rtcReleaseGeometry) release_geometry;
  decltype(&rtcCommitScene) commit_scene;
  decltype(&rtcIntersect1) intersect1;
  decltype(&rtcOccluded1) occluded1;
  decltype(&rtcReleaseScene) release_scene;
  decltype(&rtcReleaseDevice) release_device;
};

/// The table of the functions this program is linked to.
#define VBSIM_LINKED_EMBREE_GRID_API                                                                          \
  ::vbsim::test::EmbreeGridApi {                                                                            \
    rtcNewDevice, rtcNewScene, rtcNewGeometry, rtcSetSharedGeometryBuffer, rtcCommitGeometry, rtcAttachGeometry, \
        rtcReleaseGeometry, rtcCommitScene, rtcIntersect1, rtcOccluded1, rtcReleaseScene, rtcReleaseDevice     \
  }

/// Traces the grid; false (with a message) when a function is missing or `out` cannot be written.
inline bool trace_embree_grid(const EmbreeGridApi& e, const char* out_path) {
  const void* fs[] = {(void*)e.new_device,    (void*)e.new_scene,    (void*)e.new_geometry,
                      (void*)e.set_shared_buffer, (void*)e.commit_geometry, (void*)e.attach_geometry,
                      (void*)e.release_geometry, (void*)e.commit_scene, (void*)e.intersect1,
                      (void*)e.occluded1,     (void*)e.release_scene, (void*)e.release_device};
  for (const void* f : fs)
    if (!f) return std::fprintf(stderr, "embree grid: an Embree function is missing\n"), false;
  FILE* out = std::fopen(out_path, "w");
  if (!out) return std::perror(out_path), false;
  static const float ground[4][3] = {{-1, -1, 0}, {1, -1, 0.2f}, {1, 1, 0.1f}, {-1, 1, -0.1f}};
  static const float upper[4][3] = {{-0.3f, -0.3f, 0.6f}, {0.3f, -0.3f, 0.6f}, {0.3f, 0.3f, 0.7f}, {-0.3f, 0.3f, 0.7f}};
  static const unsigned square[2][3] = {{0, 1, 2}, {0, 2, 3}};
  RTCDevice device = e.new_device(nullptr);
  RTCScene scene = e.new_scene(device);
  for (const auto* vertices : {ground, upper}) {
    RTCGeometry g = e.new_geometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    e.set_shared_buffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices, 0, 12, 4);
    e.set_shared_buffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, square, 0, 12, 2);
    e.commit_geometry(g);
    e.attach_geometry(scene, g);
    e.release_geometry(g);
  }
  e.commit_scene(scene);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);  // inline in Embree's header: no library call
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      RTCRayHit rh{};
      rh.ray.org_x = -1.05f + 0.13f * static_cast<float>(i);
      rh.ray.org_y = -1.02f + 0.131f * static_cast<float>(j);
      rh.ray.org_z = 3.0f;
      rh.ray.dir_x = 0.01f;
      rh.ray.dir_z = -1.0f;
      rh.ray.tfar = 100.0f;
      rh.ray.mask = 0xffffffffu;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      e.intersect1(scene, &context, &rh);
      std::fprintf(out, "%u %u %.9g\n", rh.hit.geomID, rh.hit.primID, rh.ray.tfar);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      RTCRay shadow{};
      shadow.org_x = rh.ray.org_x + rh.ray.tfar * rh.ray.dir_x;
      shadow.org_y = rh.ray.org_y + rh.ray.tfar * rh.ray.dir_y;
      shadow.org_z = rh.ray.org_z + rh.ray.tfar * rh.ray.dir_z;
      shadow.dir_x = 0.2f;
      shadow.dir_y = 0.1f;
      shadow.dir_z = 1.0f;
      shadow.tnear = 1e-4f;
      shadow.tfar = 50.0f;
      shadow.mask = 0xffffffffu;
      e.occluded1(scene, &context, &shadow);
      std::fprintf(out, "occluded %d\n", shadow.tfar < 0 ? 1 : 0);
    }
  e.release_scene(scene);
  e.release_device(device);
  return std::fclose(out) == 0;
}

}  // namespace vbsim::test
