#include "gen/renderer_hits.h"

#include "datapath/closest_hit.h"
#include "datapath/hit_point.h"
#include "datapath/testers.h"
#include "replay/ray_emission.h"

namespace vbsim {

namespace {
SelfIntersectionMethod renderer_method(const Scene& scene) {
  SelfIntersectionMethod m;
  m.primid = true;
  m.tmin = true;
  m.tmin_eps = 1e-6f * length(scene.bounds.hi - scene.bounds.lo);
  return m;
}
}  // namespace

RendererTracer::RendererTracer(const Scene& scene, const Bvh& bvh)
    : scene_(scene), bvh_(bvh), filter_(renderer_method(scene)) {
  opt_.method = renderer_method(scene);
}

Hit RendererTracer::trace(const TraceRay& r) const {
  CandidateCounters cc;
  TraversalCounters tc;
  const EmittedRay er = emit_ray(r, scene_, opt_, nullptr);
  return closest_hit<ThreeHalfPlaneTester>(bvh_, er.ray, filter_, cc, tc);
}

TraceRay child_at_hit(const TraceRay& parent, const Hit& h, const Scene& scene, RayKind kind, Vec3f d,
                      RendererHitPoint rule, float tmax) {
  const Triangle& tri = scene.triangles[h.prim];
  TraceRay c;
  c.parent = parent.id;
  c.kind = kind;
  c.o = rule == RendererHitPoint::RayEquation ? hit_point_ray(parent.o, parent.d, h.t)
                                          : hit_point_barycentric(tri, h.u, h.v);
  c.d = d;
  c.tmax = tmax;
  c.set_parent_hit(h.prim, h.t, h.u, h.v);
  if (scene.has_normals()) {
    c.has_parent_ns = true;
    c.parent_ns = normalize(scene.shading_normal(h.prim, h.u, h.v));
  }
  c.sign = static_cast<int8_t>(parent_sign_bit(c, scene));
  return c;
}

}  // namespace vbsim

namespace vbsim {

TraceRay shadow_child_at_hit(const TraceRay& parent, const Hit& h, const Scene& scene, Vec3f light,
                             RendererHitPoint rule) {
  TraceRay c = child_at_hit(parent, h, scene, RayKind::Shadow, Vec3f{0, 0, 1}, rule, 1.0f);
  c.d = light - c.o;
  c.sign = -1;
  c.sign = static_cast<int8_t>(parent_sign_bit(c, scene));
  return c;
}

}  // namespace vbsim
