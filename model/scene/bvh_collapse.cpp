#include "scene/bvh_collapse.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "scene/bvh_build_common.h"

namespace vbsim {

namespace {

struct Slot {
  BvhRef ref;
  Bounds3f box;
};

/// The children of binary node `index`, opened up to W slots.
template <int W>
int open_slots(const Bvh& bvh, uint32_t index, Slot (&slots)[W]) {
  const BvhNode& n = bvh.nodes[index];
  slots[0] = {n.child(0), n.child_bounds(0)};
  slots[1] = {n.child(1), n.child_bounds(1)};
  int used = 2;
  while (used < W) {
    int widest = -1;
    double widest_area = -1.0;
    for (int c = 0; c < used; ++c) {
      if (slots[c].ref.is_leaf()) continue;
      const double area = bvh_build::surface_area(slots[c].box);
      if (area > widest_area) {
        widest = c;
        widest_area = area;
      }
    }
    if (widest < 0) break;  // only leaves left
    const BvhNode& open = bvh.nodes[slots[widest].ref.index];
    for (int c = used - 1; c > widest; --c) slots[c + 1] = slots[c];
    slots[widest] = {open.child(0), open.child_bounds(0)};
    slots[widest + 1] = {open.child(1), open.child_bounds(1)};
    ++used;
  }
  return used;
}

/// Appends the wide subtree of binary node `index`; returns its wide index.
template <int W>
uint32_t collapse(const Bvh& bvh, uint32_t index, int depth, std::vector<WideBvhNode<W>>& out, int& max_depth) {
  max_depth = std::max(max_depth, depth + 1);  // a leaf below this node
  Slot slots[W];
  const int used = open_slots<W>(bvh, index, slots);
  const auto at = static_cast<uint32_t>(out.size());
  out.emplace_back().clear();
  for (int c = 0; c < used; ++c) {
    BvhRef r = slots[c].ref;
    if (!r.is_leaf()) r = BvhRef{collapse<W>(bvh, r.index, depth + 1, out, max_depth), 0};
    out[at].set_child(c, slots[c].box, r);  // indexed after the recursion: `out` may have grown
  }
  out[at].children = static_cast<uint32_t>(used);
  return at;
}

template <int W>
void collapse_into(Bvh& bvh, std::vector<WideBvhNode<W>>& out) {
  out.clear();
  out.reserve(bvh.nodes.size());
  int depth = 1;
  if (!bvh.tris.empty() && !bvh.root.is_leaf()) collapse<W>(bvh, 0, 1, out, depth);
  bvh.wide_depth = bvh.tris.empty() ? 0 : depth;
}

}  // namespace

void collapse_bvh(Bvh& bvh, int width) {
  if (width != 2 && width != 4 && width != 8)
    throw std::invalid_argument(fmt::format("bvh.width must be 2, 4 or 8, got {}", width));
  if (width != 2 && !bvh.low_precision_node.empty())
    throw std::invalid_argument("bvh.width 4 and 8 take no bvh.low_precision: nodes of two precisions are binary");
  bvh.nodes4.clear();
  bvh.nodes8.clear();
  bvh.width = width;
  bvh.wide_depth = bvh.depth;
  if (width == 4) collapse_into(bvh, bvh.nodes4);
  if (width == 8) collapse_into(bvh, bvh.nodes8);
}

}  // namespace vbsim
