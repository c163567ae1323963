// What the two BVH builders (bvh_builder.cpp: Embree's rtcBuildBVH;
// sweep_sah_builder.cpp: vbsim's full-sweep SAH) share: the options' checks,
// a triangle's box, box areas (also the precision marking's and the tree
// statistics') and the order of an interior node's children (bvh.h).
// Internal to model/scene.
#pragma once
#include <cstddef>

#include "scene/bvh.h"

namespace vbsim::bvh_build {

/// Throws std::invalid_argument for a leaf size outside 1..kMaxBvhLeafSize or a
/// traversal cost outside (0, kMaxBvhTraversalCost].
void check_options(const BvhBuildOptions& options);

/// The exact float32 box of triangle `index` of `scene`; throws SceneError
/// naming the scene and the triangle when a vertex is not finite.
Bounds3f checked_triangle_bounds(const Scene& scene, size_t index);

/// The smallest box holding `a` and `b`.
Bounds3f merge(const Bounds3f& a, const Bounds3f& b);

/// Surface area (in double) of a box; 0 for an inverted (empty) one.
double surface_area(const Bounds3f& b);

/// An interior node's split axis and child order (bvh.h): the axis along which
/// the centres of its two subtrees' boxes differ most (ties: lowest axis), and
/// whether the subtrees must be swapped so that child 0's centre is not above
/// child 1's on it.
struct ChildOrder {
  int axis;
  bool swap;
};
ChildOrder order_children(const Bounds3f& first, const Bounds3f& second);

}  // namespace vbsim::bvh_build
