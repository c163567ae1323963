// Certified floating-point filter for the exact oracle: double-precision ray/box
// and ray/triangle tests whose answers come with a proven error bound, so that a
// "certain" answer always equals the exact rational one. What the filter cannot
// certify it reports as unknown, and the oracle decides it in rationals.
// The derivation of every bound is in certified_filter.cpp.
#pragma once
#include "exact/exact_geometry.h"

namespace vbsim {

/// Double-precision view of one intended ray, with the origin's rounding error.
struct FilterRay {
  bool usable = false;  ///< false: nothing can be certified; use the exact path only
  double o[3];          ///< exact origin rounded to double
  double rd[3];         ///< |exact origin - o|, rounded up (per component)
  double o_lo[3], o_hi[3];  ///< enclosure of the exact origin
  double d[3];          ///< direction, exactly the ray's
  double tmax_lo, tmax_hi;  ///< enclosure of tmax (+inf, +inf when the ray has none)
};

/// Rounds the intended ray to doubles; `usable` is false when the direction is
/// not exactly a double, or a magnitude lies outside the range the bounds are
/// proven for (|o| <= 2^130, 2^-160 <= |d_i| <= 2^128 or d_i = 0).
FilterRay make_filter_ray(const ExactRay& ray);

enum class FilterVerdict {
  Miss,        ///< certain: the exact test does not hit this triangle
  Hit,         ///< certain: the exact test hits it at some t in [t_lo, t_hi]
  PlaneOnly,   ///< the line certainly crosses the triangle with d . Ng != 0, but
               ///< whether 0 < t < tmax is not certain (decide with exact_plane_crossing)
  Unknown,     ///< nothing certain: decide with exact_intersect
};

/// Filtered form of exact_intersect. On Hit, 0 <= t_lo <= t <= t_hi (doubles).
/// Precondition: ray.usable, and the triangle's vertices are finite floats.
FilterVerdict filter_triangle(const FilterRay& ray, const Triangle& tri, double& t_lo, double& t_hi);

/// Conservative slab test of the closed box [lo, hi] against the ray's
/// parameters 0 <= t <= t_limit: false only when no point of the box is at such
/// a t. On true, t_near is a lower bound of the box's entry parameter (>= 0).
bool filter_box(const FilterRay& ray, const float lo[3], const float hi[3], double t_limit,
                double& t_near);

}  // namespace vbsim
