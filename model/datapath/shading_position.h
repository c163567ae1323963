// Shading position for shadow rays (the shadow-terminator fix, pixnblox's gist):
// project the hit point onto the three tangent planes given by the triangle's
// vertex positions and vertex normals, interpolate those projections with the
// barycentrics. Convex-only variant: use it only when it lies above the surface
// along the shading normal, else keep the geometric point.
#pragma once
#include <array>

#include "datapath/triangle.h"
#include "datapath/vec3.h"

namespace vbsim {

/// Shading position of `p` (the point at barycentrics u, v of `tri`) with unit
/// vertex normals `normals`; `convex_only` keeps p where the surface is concave.
Vec3f shading_position(Vec3f p, const Triangle& tri, const std::array<Vec3f, 3>& normals,
                       float u, float v, Vec3f shading_normal, bool convex_only);

}  // namespace vbsim
