// The full-sweep SAH builder of sweep_sah_builder.h.
#include "scene/sweep_sah_builder.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "scene/bvh_build_common.h"

namespace vbsim {

namespace {

using bvh_build::ChildOrder;
using bvh_build::order_children;
using bvh_build::surface_area;

constexpr uint32_t kNoParent = std::numeric_limits<uint32_t>::max();

// `box` grown to hold `b` (finite boxes: plain comparisons, no NaN handling).
inline void grow(Bounds3f& box, const Bounds3f& b) {
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = b.lo[a] < box.lo[a] ? b.lo[a] : box.lo[a];
    box.hi[a] = b.hi[a] > box.hi[a] ? b.hi[a] : box.hi[a];
  }
}

// Levels of the shallowest subtree over `n` triangles with leaves of up to
// `max_leaf`, each split at the median (the larger part ceil(n / 2)).
int median_levels(uint32_t n, uint32_t max_leaf) {
  int levels = 1;
  for (; n > max_leaf; n -= n / 2) ++levels;
  return levels;
}

// Lowest axis of the box's largest extent.
int largest_axis(const Bounds3f& b) {
  int best = 0;
  for (int a = 1; a < 3; ++a)
    if (double(b.hi[a]) - b.lo[a] > double(b.hi[best]) - b.lo[best]) best = a;
  return best;
}

class SweepSahBuild {
 public:
  SweepSahBuild(const Scene& scene, const BvhBuildOptions& options)
      : scene_(scene),
        max_leaf_(static_cast<uint32_t>(options.max_leaf_size)),
        traversal_cost_(options.traversal_cost),
        block_(static_cast<uint32_t>(options.sah_block_size)) {}

  Bvh run();

 private:
  // A subtree to build: its triangles are positions [begin, end) of each order_,
  // its box is exact; it fills child `slot` of node `parent` (kNoParent: the root).
  struct Task {
    uint32_t begin, end;
    Bounds3f box;
    int depth;  // levels from the root (1)
    uint32_t parent;
    int slot;
  };
  struct Split {
    double cost = std::numeric_limits<double>::infinity();  // A_left * k + A_right * (N - k)
    int axis = 0;
    uint32_t pos = 0;  // first position of the right part
  };

  void sort_centroids();
  void sweep(int axis, uint32_t begin, uint32_t end, Split& best);
  Bounds3f range_bounds(int axis, uint32_t begin, uint32_t end) const;
  void partition(int axis, uint32_t begin, uint32_t pos, uint32_t end);
  void place(const Task& task, BvhRef ref, Bvh& bvh) const;

  const Scene& scene_;
  const uint32_t max_leaf_;
  const double traversal_cost_;
  const uint32_t block_;  // triangles priced as one test
  /// Tests `count` triangles cost: ceil(count / block_).
  double blocks(uint32_t count) const { return double((count + block_ - 1) / block_); }
  std::vector<Bounds3f> boxes_;                 // by triangle id
  std::array<std::vector<uint32_t>, 3> order_;  // triangle ids by centroid on each axis
  std::vector<double> right_area_;              // by position: area of the box of [pos, end)
  std::vector<uint8_t> left_;                   // by triangle id: in the left part of the split
  std::vector<uint32_t> right_ids_;             // scratch of partition()
};

void SweepSahBuild::sort_centroids() {
  const size_t n = scene_.triangles.size();
  std::vector<double> key(n);
  for (int axis = 0; axis < 3; ++axis) {
    for (size_t i = 0; i < n; ++i) {
      const Triangle& t = scene_.triangles[i];
      key[i] = double(t.v0[axis]) + double(t.v1[axis]) + double(t.v2[axis]);  // 3 x the centroid
    }
    std::vector<uint32_t>& order = order_[axis];
    order.resize(n);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return key[a] < key[b] || (key[a] == key[b] && a < b); });
  }
}

// Every split of [begin, end) along `axis`'s order: `best` becomes the one of
// least cost if it is below best's (so earlier axes and positions win ties).
void SweepSahBuild::sweep(int axis, uint32_t begin, uint32_t end, Split& best) {
  const std::vector<uint32_t>& order = order_[axis];
  Bounds3f right;
  for (uint32_t i = end - 1; i > begin; --i) {
    grow(right, boxes_[order[i]]);
    right_area_[i] = surface_area(right);
  }
  Bounds3f left;
  for (uint32_t i = begin; i + 1 < end; ++i) {
    grow(left, boxes_[order[i]]);
    const uint32_t k = i + 1 - begin;
    const double cost = surface_area(left) * blocks(k) + right_area_[i + 1] * blocks(end - begin - k);
    if (cost < best.cost) best = {cost, axis, i + 1};
  }
}

Bounds3f SweepSahBuild::range_bounds(int axis, uint32_t begin, uint32_t end) const {
  Bounds3f b;
  for (uint32_t i = begin; i < end; ++i) grow(b, boxes_[order_[axis][i]]);
  return b;
}

// Splits [begin, end) at `pos` of `axis`'s order; the other orders are stably
// partitioned to match, so each part stays sorted on every axis.
void SweepSahBuild::partition(int axis, uint32_t begin, uint32_t pos, uint32_t end) {
  for (uint32_t i = begin; i < end; ++i) left_[order_[axis][i]] = i < pos;
  for (int other = 0; other < 3; ++other) {
    if (other == axis) continue;
    std::vector<uint32_t>& order = order_[other];
    uint32_t next_left = begin;
    right_ids_.clear();
    for (uint32_t i = begin; i < end; ++i) {
      if (left_[order[i]])
        order[next_left++] = order[i];
      else
        right_ids_.push_back(order[i]);
    }
    std::copy(right_ids_.begin(), right_ids_.end(), order.begin() + next_left);
  }
}

// Records subtree `ref` in its parent's child slot, or as the root.
void SweepSahBuild::place(const Task& task, BvhRef ref, Bvh& bvh) const {
  if (task.parent == kNoParent) {
    bvh.root_bounds = task.box;
    bvh.root = ref;
  } else {
    bvh.nodes[task.parent].set_child(task.slot, task.box, ref);
  }
}

Bvh SweepSahBuild::run() {
  Bvh bvh;
  const size_t n = scene_.triangles.size();
  if (n == 0) return bvh;  // no nodes, no triangles, depth 0
  boxes_.resize(n);
  Bounds3f all;
  for (size_t i = 0; i < n; ++i) {
    boxes_[i] = bvh_build::checked_triangle_bounds(scene_, i);
    grow(all, boxes_[i]);
  }
  sort_centroids();
  right_area_.resize(n);
  left_.resize(n);
  right_ids_.reserve(n);
  bvh.nodes.reserve(n);
  bvh.tris.reserve(n);

  // Depth first; the second child is pushed first, so the nodes come in pre-order.
  std::vector<Task> stack{{0, static_cast<uint32_t>(n), all, 1, kNoParent, 0}};
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    bvh.depth = std::max(bvh.depth, task.depth);
    const uint32_t count = task.end - task.begin;

    Split split;
    for (int axis = 0; axis < 3; ++axis) sweep(axis, task.begin, task.end, split);
    const double area = surface_area(task.box);
    const bool leaf_cheaper = blocks(count) * area <= traversal_cost_ * area + split.cost;
    const uint32_t larger = std::max(split.pos - task.begin, task.end - split.pos);
    const bool too_deep = count > 1 && task.depth + median_levels(larger, max_leaf_) > kMaxSweepSahDepth;
    if (count <= max_leaf_ && (leaf_cheaper || too_deep)) {
      const BvhRef leaf{static_cast<uint32_t>(bvh.tris.size()), count};
      for (uint32_t i = task.begin; i < task.end; ++i) {
        const uint32_t id = order_[0][i];
        bvh.tris.push_back(BvhTriangle{scene_.triangles[id], id});
      }
      place(task, leaf, bvh);
      continue;
    }
    if (leaf_cheaper || too_deep) split = {0.0, largest_axis(task.box), task.begin + count / 2};

    const Bounds3f left = range_bounds(split.axis, task.begin, split.pos);
    const Bounds3f right = range_bounds(split.axis, split.pos, task.end);
    partition(split.axis, task.begin, split.pos, task.end);
    const auto index = static_cast<uint32_t>(bvh.nodes.size());
    bvh.nodes.emplace_back();
    place(task, BvhRef{index, 0}, bvh);
    const ChildOrder order = order_children(left, right);
    bvh.nodes[index].axis = static_cast<uint32_t>(order.axis);
    Task first{task.begin, split.pos, left, task.depth + 1, index, 0};
    Task second{split.pos, task.end, right, task.depth + 1, index, 1};
    if (order.swap) {
      std::swap(first.begin, second.begin);
      std::swap(first.end, second.end);
      std::swap(first.box, second.box);
    }
    stack.push_back(second);
    stack.push_back(first);
  }
  return bvh;
}

}  // namespace

Bvh build_sweep_sah_bvh(const Scene& scene, const BvhBuildOptions& options) {
  bvh_build::check_options(options);
  return SweepSahBuild(scene, options).run();
}

}  // namespace vbsim
