#include "gen/paths_generator.h"

#include <cmath>
#include <stdexcept>

#include "datapath/closest_hit.h"
#include "datapath/hit_point.h"
#include "datapath/testers.h"
#include "gen/optics.h"
#include "gen/seeded_random.h"
#include "replay/ray_emission.h"

namespace vbsim {

namespace {

class PathBuilder {
 public:
  PathBuilder(const Scene& scene, const Bvh& bvh, const PathsParams& p, Vec3f light)
      : scene_(scene), bvh_(bvh), p_(p), light_(light), rng_(p.seed),
        filter_(tracer_method(scene)) {
    tracer_opt_.method = tracer_method(scene);
  }

  void run(Vec3f camera, Vec3f center, float radius, std::vector<TraceRay>& out) {
    out_ = &out;
    for (int path = 0; path < p_.paths; ++path) {
      const DVec3 right{1, 0, 0}, up{0, 1, 0};
      // The vertical offset is drawn first: the order the generated traces were made with.
      const double dy = rng_.uniform(-0.7, 0.7) * radius;
      const double dx = rng_.uniform(-0.7, 0.7) * radius;
      const DVec3 target = to_dvec(center) + (dx * right + dy * up);
      TraceRay r;
      r.kind = RayKind::Primary;
      r.o = camera;
      r.d = to_vec3f(target - to_dvec(camera));
      const bool ray_equation = p_.hit_points == PathsHitPoints::Alternate ? path % 2 == 0
                                                                           : p_.hit_points == PathsHitPoints::RayEquation;
      trace_path(r, ray_equation, 0);
    }
  }

 private:
  static SelfIntersectionMethod tracer_method(const Scene& scene) {
    SelfIntersectionMethod m;
    m.primid = true;
    m.tmin = true;
    m.tmin_eps = 1e-6f * length(scene.bounds.hi - scene.bounds.lo);
    return m;
  }

  /// Emits `r` into the trace and, when it hits, its children (recursively).
  void trace_path(TraceRay r, bool ray_equation, int depth) {
    r.id = next_id_++;
    out_->push_back(r);
    if (r.kind == RayKind::Shadow) return;
    CandidateCounters cc;
    TraversalCounters tc;
    const EmittedRay er = emit_ray(r, scene_, tracer_opt_, nullptr);
    const Hit h = closest_hit<ThreeHalfPlaneTester>(bvh_, er.ray, filter_, cc, tc);
    if (!h.valid() || depth >= p_.max_depth) return;
    spawn_children(r, h, ray_equation, depth);
  }

  void spawn_children(const TraceRay& parent, const Hit& h, bool ray_equation, int depth) {
    const Triangle& tri = scene_.triangles[h.prim];
    const Vec3f p = ray_equation ? hit_point_ray(parent.o, parent.d, h.t)
                                 : hit_point_barycentric(tri, h.u, h.v);
    const DVec3 ng = dunit(to_dvec(geometric_normal(tri)));
    const DVec3 d = dunit(to_dvec(parent.d));
    DVec3 ns = ng;
    if (scene_.has_normals()) ns = dunit(to_dvec(scene_.shading_normal(h.prim, h.u, h.v)));
    // Normals facing the incoming ray, for reflection and diffuse children.
    const double side = ddot(d, ng) < 0 ? 1.0 : -1.0;
    const DVec3 ng_in = side * ng, ns_in = (ddot(ns, ng_in) < 0 ? -1.0 : 1.0) * ns;

    TraceRay child;
    child.parent = parent.id;
    child.set_parent_hit(h.prim, h.t, h.u, h.v);
    if (scene_.has_normals()) {
      child.has_parent_ns = true;
      child.parent_ns = to_vec3f(ns);
    }
    child.o = p;

    TraceRay shadow = child;
    shadow.kind = RayKind::Shadow;
    shadow.d = light_ - p;
    shadow.tmax = 1.0f;
    emit_child(shadow);

    TraceRay refl = child;
    refl.kind = RayKind::Reflect;
    refl.d = to_vec3f(mirror(d, ns_in));

    TraceRay refr = child;
    refr.kind = RayKind::Refract;
    const bool entering = ddot(d, ng) < 0;
    const double eta = entering ? 1.0 / p_.ior : p_.ior;
    if (const auto t = refracted(d, ng_in, eta)) {
      refr.d = to_vec3f(*t);
    } else {
      refr.kind = RayKind::Reflect;  // total internal reflection
      refr.d = to_vec3f(mirror(d, ng_in));
    }

    TraceRay diff = child;
    diff.kind = RayKind::Diffuse;
    const DVec3 s = to_dvec(rng_.unit_vector());
    diff.d = to_vec3f(dunit(ng_in + s));  // cosine-weighted about the facing normal
    if (diff.d == Vec3f{0, 0, 0}) diff.d = to_vec3f(ng_in);

    const uint64_t pick = rng_.below(3);
    TraceRay* kids[3] = {&refl, &refr, &diff};
    for (int i = 0; i < 3; ++i) {
      if (static_cast<uint64_t>(i) == pick) continue;
      emit_child(*kids[i]);
    }
    set_sign(*kids[pick]);
    trace_path(*kids[pick], ray_equation, depth + 1);
  }

  void set_sign(TraceRay& r) { r.sign = parent_sign_bit(r, scene_); }

  void emit_child(TraceRay r) {
    set_sign(r);
    r.id = next_id_++;
    out_->push_back(r);
  }

  const Scene& scene_;
  const Bvh& bvh_;
  const PathsParams& p_;
  Vec3f light_;
  SeededRandom rng_;
  ReplayOptions tracer_opt_;
  CandidateFilter filter_;
  std::vector<TraceRay>* out_ = nullptr;
  int64_t next_id_ = 0;
};

}  // namespace

PathsHitPoints paths_hit_point_mode(const std::string& text) {
  if (text == "both") return PathsHitPoints::Alternate;
  if (text == "ray") return PathsHitPoints::RayEquation;
  if (text == "barycentric") return PathsHitPoints::Barycentric;
  throw std::runtime_error("option '--set hitpoint=" + text + "': expected ray, barycentric or both");
}

GeneratedPaths generate_paths(const Scene& scene, const Bvh& bvh, const PathsParams& params) {
  const Vec3f lo = scene.bounds.lo, hi = scene.bounds.hi;
  const Vec3f center = 0.5f * (lo + hi);
  const float radius = 0.5f * length(hi - lo);
  GeneratedPaths g;
  g.light = center + radius * Vec3f{0.6f, 2.0f, 0.9f};
  const Vec3f camera = center + radius * Vec3f{0.15f, 0.35f, 2.5f};
  PathBuilder(scene, bvh, params, g.light).run(camera, center, radius, g.rays);
  return g;
}

}  // namespace vbsim
