#include "gen/surface_children.h"

#include "gen/optics.h"

namespace vbsim {

SurfaceChildren glass_children(const TraceRay& parent, const Hit& h, const Scene& scene, double ior,
                               RendererHitPoint rule) {
  const DVec3 d = dunit(to_dvec(parent.d));
  const DVec3 ng = dunit(to_dvec(geometric_normal(scene.triangles[h.prim])));
  const bool entering = ddot(d, ng) < 0;  // arriving on the front (outer) side
  const DVec3 n_in = entering ? ng : -1.0 * ng;
  SurfaceChildren c;
  c.reflect = child_at_hit(parent, h, scene, RayKind::Reflect, to_vec3f(mirror(d, n_in)), rule);
  const auto t = refracted(d, n_in, entering ? 1.0 / ior : ior);
  c.total_internal = !t;
  c.transmit = t ? child_at_hit(parent, h, scene, RayKind::Refract, to_vec3f(*t), rule) : c.reflect;
  return c;
}

}  // namespace vbsim
