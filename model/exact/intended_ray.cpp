// The trace spec's intended ray (section "The exact answer", steps 1 and 2).
#include <cmath>
#include <stdexcept>
#include <string>

#include "exact/exact_plane.h"
#include "exact/oracle.h"

namespace vbsim {

ExactRay intended_ray(const TraceRay& ray, const Scene& scene, const ParentRay* parent) {
  ExactRay out;
  out.d = to_exact(ray.d);
  out.mask = ray.mask;
  if (std::isnan(ray.tmax))
    throw std::invalid_argument("intended_ray: ray " + std::to_string(ray.id) + ": tmax is NaN");
  if (std::isinf(ray.tmax)) {
    // +inf: no upper end; -inf: an empty interval, the same as tmax = 0.
    out.has_tmax = ray.tmax < 0;
    out.tmax = 0;
  } else {
    out.has_tmax = true;
    out.tmax = mpq_class(static_cast<double>(ray.tmax));
  }
  if (ray.parent_prim < 0) {  // camera ray: o as given
    out.o = to_exact(ray.o);
    return out;
  }
  if (ray.parent_prim >= scene.size())
    throw std::out_of_range("intended_ray: ray " + std::to_string(ray.id) + ": parent_prim " +
                            std::to_string(ray.parent_prim) + " out of range (scene has " +
                            std::to_string(scene.size()) + " triangles)");
  const Triangle& tri = scene.triangles[static_cast<size_t>(ray.parent_prim)];
  // 1. Where the parent ray, as given in the trace, meets the parent triangle's plane.
  if (parent && exact_plane_point(parent->o, parent->d, tri, out.o)) return out;
  // 2. The barycentric point at parent_uv.
  if (ray.has_parent_uv) {
    out.o = exact_barycentric_point(tri, ray.parent_u, ray.parent_v);
    return out;
  }
  // 3. The projection of o onto the plane (o itself when the plane is undefined).
  out.o = exact_degenerate(tri) ? to_exact(ray.o) : exact_projection(ray.o, tri);
  return out;
}

}  // namespace vbsim
