// Mesh shapes the scenarios build scenes from: UV spheres, boxes and flat
// quads, as triangles (outward winding: Ng = (v1 - v0) x (v2 - v0) points out
// of a closed shape) with per-corner shading normals. Every vertex is computed
// once in double and rounded to float32, so neighbouring triangles share
// bit-identical corners and closed shapes stay closed.
#pragma once
#include <array>
#include <vector>

#include "datapath/triangle.h"

namespace vbsim {

struct Mesh {
  std::vector<Triangle> triangles;
  std::vector<std::array<Vec3f, 3>> normals;  ///< one per triangle, per corner
  void append(const Mesh& other);
  int32_t size() const { return static_cast<int32_t>(triangles.size()); }
};

/// Sphere around `center` with `segments` steps of longitude and `rings` of
/// latitude (poles on the z axis, one vertex each); shading normals are the
/// exact unit directions from the centre, rounded to float.
Mesh uv_sphere(Vec3f center, double radius, int segments, int rings);

/// Axis-aligned box [lo, hi], two triangles per face; shading normals are the face normals.
Mesh box_mesh(Vec3f lo, Vec3f hi);

/// Parallelogram corner, corner + e1, corner + e1 + e2, corner + e2 as two
/// triangles with Ng along e1 x e2; shading normal unit(e1 x e2).
Mesh quad_mesh(Vec3f corner, Vec3f e1, Vec3f e2);

}  // namespace vbsim
