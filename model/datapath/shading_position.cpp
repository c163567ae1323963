#include "datapath/shading_position.h"

namespace vbsim {

namespace {
Vec3f project_on_plane(Vec3f p, Vec3f origin, Vec3f unit_normal) {
  return p - dot(p - origin, unit_normal) * unit_normal;
}
}  // namespace

Vec3f shading_position(Vec3f p, const Triangle& tri, const std::array<Vec3f, 3>& normals,
                       float u, float v, Vec3f shading_normal, bool convex_only) {
  const Vec3f p0 = project_on_plane(p, tri.v0, normalize(normals[0]));
  const Vec3f p1 = project_on_plane(p, tri.v1, normalize(normals[1]));
  const Vec3f p2 = project_on_plane(p, tri.v2, normalize(normals[2]));
  const Vec3f s = (1.0f - u - v) * p0 + u * p1 + v * p2;
  if (!convex_only) return s;
  return dot(s - p, shading_normal) > 0.0f ? s : p;
}

}  // namespace vbsim
