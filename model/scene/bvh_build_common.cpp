#include "scene/bvh_build_common.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace vbsim::bvh_build {

namespace {

double centre(const Bounds3f& b, int axis) { return 0.5 * (double(b.lo[axis]) + double(b.hi[axis])); }

}  // namespace

void check_options(const BvhBuildOptions& options) {
  if (!(options.traversal_cost > 0 && options.traversal_cost <= kMaxBvhTraversalCost))
    throw std::invalid_argument(fmt::format("BvhBuildOptions.traversal_cost must be in (0, {}], got {}",
                                            kMaxBvhTraversalCost, options.traversal_cost));
  if (!valid_sah_block_size(options.sah_block_size))
    throw std::invalid_argument(fmt::format("BvhBuildOptions.sah_block_size must be a power of two in 1..{}, got {}",
                                            kMaxBvhSahBlockSize, options.sah_block_size));
  if (options.width != 2 && options.width != 4 && options.width != 8)
    throw std::invalid_argument(fmt::format("BvhBuildOptions.width must be 2, 4 or 8, got {}", options.width));
  if (options.width != 2 && options.low_precision.enabled)
    throw std::invalid_argument("BvhBuildOptions.width 4 and 8 take no low_precision: nodes of two precisions are binary");
  if (options.max_leaf_size < 1 || options.max_leaf_size > kMaxBvhLeafSize)
    throw std::invalid_argument(fmt::format("BvhBuildOptions.max_leaf_size must be in 1..{}, got {}",
                                            kMaxBvhLeafSize, options.max_leaf_size));
}

Bounds3f checked_triangle_bounds(const Scene& scene, size_t index) {
  const Triangle& t = scene.triangles[index];
  if (!is_finite(t.v0) || !is_finite(t.v1) || !is_finite(t.v2))
    throw SceneError(fmt::format("scene '{}': triangle {} has a non-finite vertex", scene.source, index));
  Bounds3f b;
  b.extend(t.v0);
  b.extend(t.v1);
  b.extend(t.v2);
  return b;
}

Bounds3f merge(const Bounds3f& a, const Bounds3f& b) {
  Bounds3f m = a;
  m.extend(b.lo);
  m.extend(b.hi);
  return m;
}

double surface_area(const Bounds3f& b) {
  const double dx = double(b.hi.x) - b.lo.x, dy = double(b.hi.y) - b.lo.y, dz = double(b.hi.z) - b.lo.z;
  if (dx < 0 || dy < 0 || dz < 0) return 0.0;
  return 2.0 * (dx * dy + dy * dz + dz * dx);
}

ChildOrder order_children(const Bounds3f& first, const Bounds3f& second) {
  int best = 0;
  double best_gap = -1.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double gap = std::fabs(centre(first, axis) - centre(second, axis));
    if (gap > best_gap) best = axis, best_gap = gap;
  }
  return {best, centre(second, best) < centre(first, best)};
}

}  // namespace vbsim::bvh_build
