#include "scene/bvh_precision.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "datapath/reduced_precision.h"
#include "scene/bvh_build_common.h"

namespace vbsim {

namespace {

using bvh_build::surface_area;

/// A / B, or 1 when B has no area (a flat parent: no ratio to speak of).
double ratio(double a, double b) { return b > 0.0 ? a / b : 1.0; }

}  // namespace

void check_bvh_precision(const BvhPrecisionMarking& m) {
  if (m.mantissa_bits < 0 || m.mantissa_bits > 22)
    throw std::invalid_argument(fmt::format("bvh.low_precision.mantissa_bits must be 0 to 22, got {}", m.mantissa_bits));
  if (!(m.t_trav_high >= 0.0 && m.t_trav_high <= 1000.0))
    throw std::invalid_argument(fmt::format("bvh.low_precision.t_trav_high must be 0 to 1000, got {}", m.t_trav_high));
  if (!(m.t_trav_low >= 0.0 && m.t_trav_low <= 1000.0))
    throw std::invalid_argument(fmt::format("bvh.low_precision.t_trav_low must be 0 to 1000, got {}", m.t_trav_low));
}

void mark_low_precision(Bvh& bvh, const BvhPrecisionMarking& m) {
  check_bvh_precision(m);
  const size_t n = bvh.nodes.size();
  bvh.low_precision_node.assign(n, 0);
  bvh.narrow_mantissa_bits = m.narrow_arithmetic ? m.mantissa_bits : -1;
  if (n == 0) return;  // a root leaf or an empty scene: no node record to mark
  const int bits = m.mantissa_bits;
  // Bottom-up (pre-order: children after their parent, so backwards): the cost
  // of each node's subtree with the node kept in full (0) or low (1) precision,
  // and the choice (bit c: child c low) each of those makes.
  std::vector<double> cost[2] = {std::vector<double>(n), std::vector<double>(n)};
  std::vector<uint8_t> choice[2] = {std::vector<uint8_t>(n), std::vector<uint8_t>(n)};
  // The box of each node as its parent's record holds it (the root's: root_bounds).
  std::vector<Bounds3f> own(n);
  own[0] = bvh.root_bounds;
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 2; ++c)
      if (!bvh.nodes[i].child(c).is_leaf()) own[bvh.nodes[i].ref[c]] = bvh.nodes[i].child_bounds(c);
  for (size_t k = n; k-- > 0;) {
    const BvhNode& node = bvh.nodes[k];
    const double parent_area[2] = {surface_area(own[k]), surface_area(round_outward(own[k], bits))};
    for (int p = 0; p < 2; ++p) {
      cost[p][k] = 0.0;
      choice[p][k] = 0;
      for (int c = 0; c < 2; ++c) {
        const BvhRef r = node.child(c);
        const Bounds3f box = node.child_bounds(c);
        const double high_cost = r.is_leaf() ? double(r.count) : cost[0][r.index];
        const double low_cost = r.is_leaf() ? double(r.count) : cost[1][r.index];
        const double high = m.t_trav_high + ratio(surface_area(box), parent_area[p]) * high_cost;
        const double low = m.t_trav_low + ratio(surface_area(round_outward(box, bits)), parent_area[p]) * low_cost;
        if (low <= high) choice[p][k] |= uint8_t(1u << c);
        cost[p][k] += low <= high ? low : high;
      }
    }
  }
  // Top-down: the root in full precision; each node's children as its own
  // precision chose. Pre-order: a node's precision is known before its children's.
  std::vector<uint8_t> low(n, 0);
  for (size_t k = 0; k < n; ++k) {
    BvhNode& node = bvh.nodes[k];
    const uint8_t ch = choice[low[k]][k];
    for (int c = 0; c < 2; ++c) {
      if (!(ch & (1u << c))) continue;
      const BvhRef r = node.child(c);
      node.set_child(c, round_outward(node.child_bounds(c), bits), r);
      if (!r.is_leaf()) low[r.index] = 1;
    }
    bvh.low_precision_node[k] = ch == 3 ? 1 : 0;
  }
}

}  // namespace vbsim
