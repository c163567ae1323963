#include "scene/embree_reference.h"

#include <cctype>
#include <stdexcept>

#include <fmt/format.h>

namespace vbsim {

namespace {

// Releases an Embree geometry once it is attached (the scene keeps its own reference).
struct GeometryHandle {
  RTCGeometry geometry;
  ~GeometryHandle() {
    if (geometry) rtcReleaseGeometry(geometry);
  }
};

// Adds `scene`'s triangles to `target` as geometry 0 (primID = triangle id).
void attach_triangles(const Scene& scene, EmbreeDevice& device, RTCScene target) {
  GeometryHandle geometry{rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE)};
  device.check("rtcNewGeometry");
  rtcSetGeometryBuildQuality(geometry.geometry, RTC_BUILD_QUALITY_HIGH);
  const size_t count = scene.triangles.size();
  // Unshared vertices: triangle k uses vertices 3k, 3k+1, 3k+2, exactly as stored.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry.geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry.geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
  device.check("rtcSetNewGeometryBuffer");
  for (size_t k = 0; k < count; ++k) {
    const Triangle& tri = scene.triangles[k];
    const Vec3f corners[3] = {tri.v0, tri.v1, tri.v2};
    for (int c = 0; c < 3; ++c) {
      for (int axis = 0; axis < 3; ++axis) vertices[9 * k + 3 * c + axis] = corners[c][axis];
      indices[3 * k + c] = static_cast<unsigned>(3 * k + c);
    }
  }
  rtcCommitGeometry(geometry.geometry);
  rtcAttachGeometryByID(target, geometry.geometry, 0);
}

/// The device settings that select `tri_accel` (empty: none); throws
/// SceneError for a name that could carry other settings.
std::string accel_settings(const std::string& tri_accel) {
  if (tri_accel.empty()) return "";
  for (char c : tri_accel)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_')
      throw SceneError(fmt::format("Embree triangle acceleration structure '{}': only letters, digits, '.' and '_' "
                                   "make a name (e.g. bvh4.triangle4v)",
                                   tri_accel));
  return "tri_accel=" + tri_accel;
}

/// An intersect context that names the triangle its filter rejects, and the
/// triangle masks and ray mask that hide others.
struct ExcludingContext {
  RTCIntersectContext context;  // first: Embree passes its address to the filter
  uint32_t exclude;
  const uint32_t* masks;  // null: every triangle has all bits
  uint32_t ray_mask;
};

void reject_excluded(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const ExcludingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const uint32_t mask = ctx->masks != nullptr ? ctx->masks[prim] : 0xffffffffu;
    if (prim == ctx->exclude || (mask & ctx->ray_mask) == 0) args->valid[i] = 0;
  }
}

RTCRay make_ray(Vec3f o, Vec3f d, float tnear, float tfar) {
  RTCRay r;
  r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
  r.tnear = tnear;
  r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
  r.time = 0.0f;
  r.tfar = tfar;
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
  return r;
}

}  // namespace

EmbreeReference::EmbreeReference(const Scene& scene, const std::string& tri_accel, bool exclusion)
    : device_(std::make_unique<EmbreeDevice>(accel_settings(tri_accel))),
      exclusion_(exclusion),
      masks_(scene.triangle_masks) {
  scene_ = rtcNewScene(device_->get());
  device_->check("rtcNewScene");
  try {
    rtcSetSceneFlags(scene_, exclusion ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION
                                       : RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

    if (!scene.triangles.empty()) attach_triangles(scene, *device_, scene_);
    rtcCommitScene(scene_);
    device_->check("scene build");
  } catch (...) {
    rtcReleaseScene(scene_);
    throw;
  }
}

EmbreeReference::~EmbreeReference() { rtcReleaseScene(scene_); }

bool EmbreeReference::intersect_in(RTCIntersectContext& context, Vec3f o, Vec3f d, float tnear, float tfar,
                                   int32_t& prim, float& t, float& u, float& v) const {
  RTCRayHit query;
  query.ray = make_ray(o, d, tnear, tfar);
  query.hit.geomID = query.hit.primID = query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &query);
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  prim = static_cast<int32_t>(query.hit.primID);
  t = query.ray.tfar;
  u = query.hit.u;
  v = query.hit.v;
  return true;
}

bool EmbreeReference::intersect(Vec3f o, Vec3f d, float tnear, float tfar, int32_t& prim, float& t, float& u,
                                float& v) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  return intersect_in(context, o, d, tnear, tfar, prim, t, u, v);
}

bool EmbreeReference::occluded(Vec3f o, Vec3f d, float tnear, float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay query = make_ray(o, d, tnear, tfar);
  rtcOccluded1(scene_, &context, &query);
  return query.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

bool EmbreeReference::intersect_excluding(Vec3f o, Vec3f d, float tnear, float tfar, int32_t exclude,
                                          int32_t& prim, float& t, float& u, float& v, uint32_t ray_mask) const {
  if (!exclusion_) throw std::logic_error("EmbreeReference::intersect_excluding on a reference built without exclusion");
  ExcludingContext ctx;
  rtcInitIntersectContext(&ctx.context);
  ctx.context.filter = reject_excluded;
  ctx.exclude = static_cast<uint32_t>(exclude);  // -1: no triangle id
  ctx.masks = masks_.empty() ? nullptr : masks_.data();
  ctx.ray_mask = ray_mask;
  return intersect_in(ctx.context, o, d, tnear, tfar, prim, t, u, v);
}

}  // namespace vbsim
