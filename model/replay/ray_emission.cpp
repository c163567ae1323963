#include "replay/ray_emission.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "datapath/hit_point.h"
#include "datapath/origin_offsets.h"
#include "datapath/shading_position.h"
#include "datapath/testers.h"

namespace vbsim {

namespace {

/// Far end of the ray's passage through the scene's bounding box (0 when it
/// never enters): where a reverse-shadow ray with no finite tmax starts.
float scene_exit_t(const Scene& scene, Vec3f o, Vec3f d) {
  float tfar = std::numeric_limits<float>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0f) continue;
    const float t0 = (scene.bounds.lo[i] - o[i]) / d[i];
    const float t1 = (scene.bounds.hi[i] - o[i]) / d[i];
    tfar = std::min(tfar, std::max(t0, t1));
  }
  return std::isfinite(tfar) && tfar > 0.0f ? tfar : 0.0f;
}

/// Start point of the child before any method acts, per the hit-point mode.
Vec3f base_origin(const TraceRay& tr, const Scene& scene, HitPointMode mode,
                  const ParentRay* parent, bool& fallback) {
  if (mode == HitPointMode::Given || tr.parent_prim < 0) return tr.o;
  if (mode == HitPointMode::Ray) {
    if (tr.has_parent_t && parent) return hit_point_ray(parent->o, parent->d, tr.parent_t);
  } else if (tr.has_parent_uv) {
    return hit_point_barycentric(scene.triangles[tr.parent_prim], tr.parent_u, tr.parent_v);
  }
  fallback = true;
  return tr.o;
}

/// offset-errbound: pbrt-v4 spawns from the barycentrics its own triangle test
/// found, so they are recomputed with that test from the parent ray (known when
/// it came before the child) on the parent triangle; failing that, from
/// parent_uv with b0 = 1 - u - v; failing that (an emission fallback), pbrt's
/// bound gamma(7) |p| is put on the given point.
Vec3f errbound_origin(const TraceRay& tr, const Scene& scene, const ParentRay* parent_ray, Vec3f p, Vec3f d,
                      OffsetOutcome& outcome, bool& fallback) {
  const Triangle& tri = scene.triangles[tr.parent_prim];
  const std::array<Vec3f, 3>* normals = scene.has_normals() ? &scene.normals[tr.parent_prim] : nullptr;
  if (parent_ray && tr.parent >= 0) {
    Ray parent;
    parent.o = parent_ray->o;
    parent.d = parent_ray->d;
    PbrtTriangleHit h;
    if (PbrtWatertightTester(parent).intersect_triangle(tri, std::numeric_limits<float>::infinity(), h))
      return offset_error_bound(p, tri, h.b0, h.b1, h.b2, normals, d, outcome);
  }
  if (tr.has_parent_uv)
    return offset_error_bound(p, tri, 1.0f - tr.parent_u - tr.parent_v, tr.parent_u, tr.parent_v, normals, d,
                              outcome);
  fallback = true;
  return offset_error_bound_at(p, tri, d, outcome);
}

Vec3f parent_shading_normal(const TraceRay& tr, const Scene& scene, Vec3f ng) {
  if (tr.has_parent_ns) return tr.parent_ns;
  if (scene.has_normals() && tr.has_parent_uv)
    return scene.shading_normal(tr.parent_prim, tr.parent_u, tr.parent_v);
  return ng;
}

}  // namespace

const char* hit_point_mode_name(HitPointMode m) {
  switch (m) {
    case HitPointMode::Given: return "given";
    case HitPointMode::Ray: return "ray";
    default: return "barycentric";
  }
}

bool parse_hit_point_mode(const std::string& s, HitPointMode& out) {
  if (s == "given") out = HitPointMode::Given;
  else if (s == "ray") out = HitPointMode::Ray;
  else if (s == "barycentric") out = HitPointMode::Barycentric;
  else return false;
  return true;
}

uint8_t parent_sign_bit(const TraceRay& tr, const Scene& scene) {
  if (tr.sign >= 0) return static_cast<uint8_t>(tr.sign);
  if (tr.parent_prim < 0) return 0;
  return dot(tr.d, geometric_normal(scene.triangles[tr.parent_prim])) < 0.0f ? 1 : 0;
}

EmittedRay emit_ray(const TraceRay& tr, const Scene& scene, const ReplayOptions& opt,
                    const ParentRay* parent) {
  const SelfIntersectionMethod& m = opt.method;
  EmittedRay out;
  Ray& r = out.ray;
  r.d = tr.d;
  r.tmin = tr.tmin;
  r.tmax = tr.tmax;
  r.kind = tr.kind;
  r.parent_prim = tr.parent_prim;
  r.mask = tr.mask;
  r.sign = parent_sign_bit(tr, scene);
  if (parent) out.parent = *parent;
  Vec3f p = base_origin(tr, scene, opt.hit_point, parent, out.emission_fallback);

  if (tr.parent_prim >= 0) {
    const Triangle& tri = scene.triangles[tr.parent_prim];
    const Vec3f ng = geometric_normal(tri);
    const bool shadow = tr.kind == RayKind::Shadow;
    OffsetOutcome outcome = OffsetOutcome::Reference;
    if (shadow && (m.shading_position || m.shading_position_always)) {
      if (scene.has_normals() && tr.has_parent_uv) {
        const Vec3f s = shading_position(p, tri, scene.normals[tr.parent_prim], tr.parent_u, tr.parent_v,
                                         parent_shading_normal(tr, scene, ng), !m.shading_position_always);
        if (is_finite(s)) p = s;
        else outcome = OffsetOutcome::NotOffset;  // a vertex normal of zero length
      } else {
        out.emission_fallback = true;  // needs vertex normals and parent_uv
      }
    }
    if (m.offset_errbound) p = errbound_origin(tr, scene, parent, p, r.d, outcome, out.emission_fallback);
    if (m.offset_adaptive) p = offset_adaptive(p, tri, r.d, m.adaptive, outcome);
    if (m.offset_normal)
      p = offset_along_normal(p, parent_shading_normal(tr, scene, ng), tri, r.d, m.offset_normal_eps, outcome);
    if (m.offset_direction) p = offset_along_direction(p, r.d, m.offset_direction_eps);
    out.offset_fallback = outcome != OffsetOutcome::Reference;
  }
  r.o = p;
  if (m.tmin) r.tmin = std::max(r.tmin, m.tmin_eps / length(r.d));

  if (m.reverse_shadow && tr.kind == RayKind::Shadow) {
    const float t_light = std::isfinite(r.tmax) ? r.tmax : scene_exit_t(scene, r.o, r.d);
    r.o = r.o + t_light * r.d;
    r.d = -r.d;
    r.tmax = t_light;
    r.sign ^= 1u;  // the sign bit belongs to the direction, which flipped
    out.reversed = true;
  }
  return out;
}

}  // namespace vbsim
