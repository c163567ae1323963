// Exact geometry: rational (GMP mpq) points, rays and the ray/triangle test the
// trace spec's exact answer is defined by. Every float32 input converts to a
// rational exactly; nothing here rounds.
#pragma once
#include <gmpxx.h>

#include <cstdint>

#include "datapath/triangle.h"
#include "datapath/vec3.h"
#include "trace/trace_record.h"

namespace vbsim {

struct ExactVec3 {
  mpq_class x, y, z;
};
ExactVec3 to_exact(Vec3f v);

/// The intended ray of the trace spec: origin (exact), direction d (float32,
/// exact), open lower end at 0, upper end tmax (open; +inf when has_tmax false).
struct ExactRay {
  ExactVec3 o;
  ExactVec3 d;
  bool has_tmax = false;
  mpq_class tmax;
  /// The ray's mask: triangles whose mask (Scene::triangle_masks) shares no
  /// bit with it are not there for this ray (the trace's ray masks).
  uint32_t mask = 0xffffffffu;
};

/// Exact hit of the intended ray on one triangle: hit when the line meets the
/// closed triangle at 0 < t < tmax and the triangle's plane does not contain the ray.
struct ExactHit {
  bool hit = false;
  mpq_class t;
};
ExactHit exact_intersect(const ExactRay& ray, const Triangle& tri);

/// Exact point where the ray o + t d meets the plane of `tri`; false when d is
/// parallel to the plane.
bool exact_plane_point(Vec3f o, Vec3f d, const Triangle& tri, ExactVec3& out);
/// Exact point (1-u-v) v0 + u v1 + v v2.
ExactVec3 exact_barycentric_point(const Triangle& tri, float u, float v);
/// Exact orthogonal projection of p onto the plane of `tri` (tri not degenerate).
ExactVec3 exact_projection(Vec3f p, const Triangle& tri);

}  // namespace vbsim
