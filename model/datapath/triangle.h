// Triangle: three float32 vertices in the scene file's order.
// Sign convention (trace spec): the geometric normal is Ng = (v1 - v0) x (v2 - v0),
// unnormalised; its side is the triangle's front.
#pragma once
#include "datapath/vec3.h"

namespace vbsim {

struct Triangle {
  Vec3f v0, v1, v2;
};

/// Ng = (v1 - v0) x (v2 - v0), in float32, unnormalised.
inline Vec3f geometric_normal(const Triangle& tri) { return cross(tri.v1 - tri.v0, tri.v2 - tri.v0); }

/// True when the two triangles share at least one vertex position exactly.
inline bool shares_vertex(const Triangle& a, const Triangle& b) {
  const Vec3f av[3] = {a.v0, a.v1, a.v2};
  const Vec3f bv[3] = {b.v0, b.v1, b.v2};
  for (const Vec3f& p : av)
    for (const Vec3f& q : bv)
      if (p == q) return true;
  return false;
}

}  // namespace vbsim
