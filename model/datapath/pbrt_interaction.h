// The parts of pbrt-v4's SurfaceInteraction that spawning a ray from a
// triangle hit uses, computed as pbrt-v4 computes them (float32, its operation
// order; datapath/pbrt_float.h):
//   Triangle::InteractionFromIntersection (shapes.h):
//     pHit = b0 p0 + b1 p1 + b2 p2,
//     pError = gamma(7) (|b0 p0| + |b1 p1| + |b2 p2|) per component,
//     the point as an interval (Point3fi(pHit, pError)),
//     n = Normalize(Cross(p0 - p2, p1 - p2)), and with per-vertex normals
//     ns = b0 n0 + b1 n1 + b2 n2 (normalised when its squared length is > 0,
//     else n) and n = FaceForward(n, ns) (SetShadingGeometry with an
//     authoritative orientation);
//   OffsetRayOrigin(pi, n, w) (ray.h): offset dot(|n|, error) along n, on the
//     side of w (negated when dot(w, n) < 0), added to the interval's midpoint,
//     each offset component then moved one float further outward;
//   SpawnRayTo(pi, n, time, p2): direction p2 - midpoint, origin offset along it.
// Not modelled: reverseOrientation / transformSwapsHandedness (vbsim scenes
// have neither; their effect, a negated n, moves no origin, since the offset
// takes its side from w, except when dot(w, n) is exactly 0), textures, media.
#pragma once
#include <array>

#include "datapath/pbrt_float.h"
#include "datapath/triangle.h"

namespace vbsim::pbrt {

struct SurfacePoint {
  PointInterval pi;  ///< the hit point and its error bound
  Vec3f n;           ///< unit geometric normal (NaN when the float cross product is 0 or overflows)
};

/// The interaction of a hit at barycentrics (b0, b1, b2) of `tri`; `normals`
/// (may be null) are the triangle's per-vertex shading normals.
SurfacePoint triangle_interaction(const Triangle& tri, float b0, float b1, float b2,
                                  const std::array<Vec3f, 3>* normals);

/// OffsetRayOrigin(pi, n, w).
Vec3f offset_ray_origin(const PointInterval& pi, Vec3f n, Vec3f w);

/// SpawnRayTo's direction toward `target`: target - pi's midpoint.
inline Vec3f spawn_direction_to(const PointInterval& pi, Vec3f target) { return target - pi.point(); }

}  // namespace vbsim::pbrt
