// Exact plane of a triangle: degeneracy, and the crossing of a ray with the
// plane without the edge tests (the cheap part of exact_intersect, for when the
// edges are already known to pass).
#pragma once
#include "exact/exact_geometry.h"

namespace vbsim {

/// True when Ng = (v1 - v0) x (v2 - v0) is exactly zero (collinear vertices).
bool exact_degenerate(const Triangle& tri);

/// True when d . Ng != 0 and the ray's line meets the triangle's plane at
/// 0 < t < tmax (tmax open, none when !has_tmax); then `t` holds that exact t.
/// The edges are not tested: equal to exact_intersect when the line is known
/// to meet the closed triangle.
bool exact_plane_crossing(const ExactRay& ray, const Triangle& tri, mpq_class& t);

}  // namespace vbsim
