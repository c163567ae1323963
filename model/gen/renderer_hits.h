// The renderer side of a generated trace: finding where a ray hits (with the
// three-half-plane tester, primitive-ID exclusion and a tmin of 1e-6 of the
// scene's diagonal, as a renderer might) and spawning children from that hit
// with the parent data a replay's methods need (parent_prim, parent_t,
// parent_uv, parent_ns when the scene has vertex normals, the sign bit). The
// child's origin is the raw hit point, before any self-intersection offset,
// computed by the ray equation or by barycentrics.
#pragma once
#include <vector>

#include "datapath/candidate_filter.h"
#include "datapath/hit.h"
#include "replay/replay_options.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/trace_record.h"

namespace vbsim {

/// How the path generator computes a child ray's origin from its parent's hit
/// (a type of its own: gen/scenario_trace_builder.h has another rule).
enum class RendererHitPoint { RayEquation, Barycentric };

class RendererTracer {
 public:
  /// `scene` and `bvh` must outlive the tracer.
  RendererTracer(const Scene& scene, const Bvh& bvh);
  /// Closest hit of `r` as the renderer finds it (invalid Hit on a miss).
  Hit trace(const TraceRay& r) const;

 private:
  const Scene& scene_;
  const Bvh& bvh_;
  ReplayOptions opt_;
  CandidateFilter filter_;
};

/// Child of `parent` (whose id is set) at its hit `h`: kind, direction d,
/// tmax, origin by `rule`, parent data and sign bit filled; id left 0.
TraceRay child_at_hit(const TraceRay& parent, const Hit& h, const Scene& scene, RayKind kind, Vec3f d,
                      RendererHitPoint rule, float tmax = INFINITY);

/// Shadow child of `parent` at its hit `h` toward the point `light`
/// (d = light - o, tmax 1), built as child_at_hit builds its children.
TraceRay shadow_child_at_hit(const TraceRay& parent, const Hit& h, const Scene& scene, Vec3f light,
                             RendererHitPoint rule);

/// The rays of a trace under construction: ids are positions, so parents
/// (added first) precede their children.
struct TraceRays {
  std::vector<TraceRay> rays;
  /// Appends `r` with the next id and returns the stored ray.
  const TraceRay& add(TraceRay r) {
    r.id = static_cast<int64_t>(rays.size());
    rays.push_back(r);
    return rays.back();
  }
};

}  // namespace vbsim
