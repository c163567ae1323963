#include "scene_registry.h"

#include <atomic>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <unordered_map>

#include "capture/instance_transform.h"
#include "capture_output.h"
#include "real_embree.h"

namespace vbsim::shim {

namespace {

using capture::RawGeometry;
using capture::RawGeometryStatus;

struct Binding {
  RTCFormat format = RTC_FORMAT_UNDEFINED;
  const void* ptr = nullptr;  // shared or new buffer
  RTCBuffer buffer = nullptr;  // else an RTCBuffer at `offset`
  std::size_t offset = 0, stride = 0, count = 0;
};

struct Geometry {
  RTCGeometryType type = RTC_GEOMETRY_TYPE_TRIANGLE;
  unsigned time_steps = 1;
  bool enabled = true;
  uint32_t filters = 0;  // RawGeometryFilter bits
  uint32_t mask = 0xffffffffu;  // rtcSetGeometryMask (Embree's default: every ray sees the geometry)
  // Instances: the instanced scene and the time-step-0 transform (row-major 3x4).
  RTCScene instanced = nullptr;
  bool has_transform = false, unsupported_transform = false;
  float xfm[12] = {};
  std::map<std::pair<int, unsigned>, Binding> buffers;  // (RTCBufferType, slot)
};

struct Scene {
  uint32_t ordinal = 0;
  uint32_t commit = 0;
  std::map<unsigned, RTCGeometry> attached;  // geomID -> geometry, ascending
  std::string last_snapshot;  // bytes after the header, to skip unchanged commits
};

struct Registry {
  std::mutex m;
  std::unordered_map<RTCGeometry, Geometry> geometries;
  std::unordered_map<RTCScene, Scene> scenes;
  uint32_t next_scene = 0;
  std::atomic<uint64_t> epoch{1};  // bumped whenever a stamp may change
};

Registry& registry() {
  static Registry* r = new Registry;  // never destroyed: rays may arrive during exit
  return *r;
}

const unsigned char* data_of(const Binding& b) {
  if (b.ptr) return static_cast<const unsigned char*>(b.ptr);
  if (!b.buffer) return nullptr;
  VBSIM_REAL(rtcGetBufferData);
  const auto* base = static_cast<const unsigned char*>(real(b.buffer));
  return base ? base + b.offset : nullptr;
}

/// An instance's entry: its RawGeometry, then its RawInstance when captured
/// (an instanced scene committed before, one time step, a matrix transform).
void append_instance(std::string& out, RawGeometry rg, const Geometry& g, const Registry& r) {
  const auto scene = g.instanced ? r.scenes.find(g.instanced) : r.scenes.end();
  RawGeometryStatus status = RawGeometryStatus::Captured;
  if (!g.enabled) status = RawGeometryStatus::Disabled;
  else if (g.time_steps != 1) status = RawGeometryStatus::MotionBlur;
  else if (g.unsupported_transform) status = RawGeometryStatus::BadFormat;
  else if (scene == r.scenes.end() || scene->second.commit == 0 || !g.has_transform)
    status = RawGeometryStatus::MissingBuffer;
  rg.status = static_cast<uint32_t>(status);
  out.append(reinterpret_cast<const char*>(&rg), sizeof rg);
  if (status != RawGeometryStatus::Captured) return;
  capture::RawInstance ri{};
  ri.scene = scene->second.ordinal;
  ri.commit = scene->second.commit;
  std::memcpy(ri.xfm, g.xfm, sizeof ri.xfm);
  out.append(reinterpret_cast<const char*>(&ri), sizeof ri);
}

/// One geometry's entry in a snapshot: its RawGeometry, then its data when captured.
void append_geometry(std::string& out, unsigned geom_id, const Geometry& g, const Registry& r) {
  RawGeometry rg{};
  rg.geom_id = geom_id;
  rg.type = static_cast<uint32_t>(g.type);
  rg.filters = g.filters;
  rg.mask = g.mask;
  if (g.type == RTC_GEOMETRY_TYPE_INSTANCE) return append_instance(out, rg, g, r);
  const auto vb = g.buffers.find({RTC_BUFFER_TYPE_VERTEX, 0});
  const auto ib = g.buffers.find({RTC_BUFFER_TYPE_INDEX, 0});
  const unsigned char* vdata = vb == g.buffers.end() ? nullptr : data_of(vb->second);
  const unsigned char* idata = ib == g.buffers.end() ? nullptr : data_of(ib->second);
  const bool quads = g.type == RTC_GEOMETRY_TYPE_QUAD;  // each quad: 4 indices, 2 triangles as Embree splits it
  RawGeometryStatus status = RawGeometryStatus::Captured;
  if (g.type != RTC_GEOMETRY_TYPE_TRIANGLE && !quads) status = RawGeometryStatus::NotTriangles;
  else if (!g.enabled) status = RawGeometryStatus::Disabled;
  else if (g.time_steps != 1) status = RawGeometryStatus::MotionBlur;
  else if (!vdata || !idata) status = RawGeometryStatus::MissingBuffer;
  else if (vb->second.format != RTC_FORMAT_FLOAT3 || ib->second.format != (quads ? RTC_FORMAT_UINT4 : RTC_FORMAT_UINT3))
    status = RawGeometryStatus::BadFormat;
  rg.status = static_cast<uint32_t>(status);
  if (status == RawGeometryStatus::Captured) {
    rg.vertex_count = static_cast<uint32_t>(vb->second.count);
    rg.triangle_count = static_cast<uint32_t>(ib->second.count);
  }
  out.append(reinterpret_cast<const char*>(&rg), sizeof rg);
  if (status != RawGeometryStatus::Captured) return;
  // The buffers as Embree sees them: element i at data + i * stride.
  for (std::size_t i = 0; i < rg.vertex_count; ++i)
    out.append(reinterpret_cast<const char*>(vdata + i * vb->second.stride), 3 * sizeof(float));
  for (std::size_t i = 0; i < rg.triangle_count; ++i)
    out.append(reinterpret_cast<const char*>(idata + i * ib->second.stride), (quads ? 4 : 3) * sizeof(uint32_t));
}

thread_local struct {
  RTCScene scene = nullptr;
  uint64_t epoch = 0;
  SceneStamp stamp;
} t_cache;

}  // namespace

void on_new_scene(RTCScene scene) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.m);
  Scene s;
  s.ordinal = r.next_scene++;
  r.scenes[scene] = std::move(s);  // a handle reused after a release starts afresh
  r.epoch.fetch_add(1);
  count_scene();
}

void on_new_geometry(RTCGeometry geometry, RTCGeometryType type) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.m);
  Geometry g;
  g.type = type;
  r.geometries[geometry] = std::move(g);
}

void on_attach(RTCScene scene, RTCGeometry geometry, unsigned geom_id) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.m);
  r.scenes[scene].attached[geom_id] = geometry;
}

void on_detach(RTCScene scene, unsigned geom_id) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.m);
  r.scenes[scene].attached.erase(geom_id);
}

namespace {

/// Applies `change` to the registry's record of `geometry`, under the registry's lock.
template <class Change>
void change_geometry(RTCGeometry geometry, Change change) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.m);
  change(r.geometries[geometry]);
}

}  // namespace

void on_enable(RTCGeometry geometry, bool enabled) {
  change_geometry(geometry, [&](Geometry& g) { g.enabled = enabled; });
}

void on_time_steps(RTCGeometry geometry, unsigned count) {
  change_geometry(geometry, [&](Geometry& g) { g.time_steps = count; });
}

void on_instanced_scene(RTCGeometry geometry, RTCScene scene) {
  change_geometry(geometry, [&](Geometry& g) { g.instanced = scene; });
}

void on_transform(RTCGeometry geometry, unsigned step, RTCFormat format, const void* xfm) {
  change_geometry(geometry, [&](Geometry& g) {
    if (step != 0) return;  // more time steps make it motion-blurred (time_steps), not captured
    g.has_transform = xfm && capture::instance_transform_row_major(static_cast<uint32_t>(format),
                                                                    static_cast<const float*>(xfm), g.xfm);
    g.unsupported_transform = !g.has_transform;
  });
}

void on_quaternion_transform(RTCGeometry geometry) {
  change_geometry(geometry, [](Geometry& g) { g.unsupported_transform = true; });
}

void on_mask(RTCGeometry geometry, uint32_t mask) {
  change_geometry(geometry, [&](Geometry& g) { g.mask = mask; });
}

void on_filter(RTCGeometry geometry, uint32_t which, bool set) {
  change_geometry(geometry, [&](Geometry& g) { g.filters = set ? (g.filters | which) : (g.filters & ~which); });
}

void on_buffer(RTCGeometry geometry, RTCBufferType type, unsigned slot, RTCFormat format, const void* ptr,
               RTCBuffer buffer, std::size_t offset, std::size_t stride, std::size_t count) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.m);
  Binding b;
  b.format = format;
  b.ptr = ptr ? static_cast<const unsigned char*>(ptr) + offset : nullptr;
  b.buffer = ptr ? nullptr : buffer;
  b.offset = offset;
  b.stride = stride;
  b.count = count;
  r.geometries[geometry].buffers[{static_cast<int>(type), slot}] = b;
}

void on_commit(RTCScene scene) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.m);
  Scene& s = r.scenes[scene];
  std::string body;
  for (const auto& [geom_id, geometry] : s.attached) append_geometry(body, geom_id, r.geometries[geometry], r);
  count_commit();
  if (s.commit > 0 && body == s.last_snapshot) return;  // the same triangles: the same snapshot
  ++s.commit;
  capture::RawSceneHeader h{};
  std::memcpy(h.magic, capture::kRawSceneMagic, sizeof h.magic);
  h.scene = s.ordinal;
  h.commit = s.commit;
  h.geometries = static_cast<uint32_t>(s.attached.size());
  std::string file(reinterpret_cast<const char*>(&h), sizeof h);
  file += body;
  write_capture_file("scene-" + capture_image() + "-" + std::to_string(s.ordinal) + "-" +
                         std::to_string(s.commit) + ".bin",
                     file);
  s.last_snapshot = std::move(body);
  r.epoch.fetch_add(1);
}

SceneStamp scene_stamp(RTCScene scene) {
  Registry& r = registry();
  const uint64_t epoch = r.epoch.load(std::memory_order_acquire);
  if (t_cache.scene == scene && t_cache.epoch == epoch) return t_cache.stamp;
  std::lock_guard<std::mutex> lock(r.m);
  SceneStamp stamp;
  const auto it = r.scenes.find(scene);
  if (it != r.scenes.end()) stamp = {it->second.ordinal, it->second.commit};
  t_cache.scene = scene;
  t_cache.epoch = epoch;
  t_cache.stamp = stamp;
  return stamp;
}

}  // namespace vbsim::shim
