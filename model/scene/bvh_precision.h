// Nodes of two precisions, as rtcore-systemc builds its tree: a child's box is
// kept either in full float32 precision or rounded outward to a narrow format
// (fewer fraction bits: a smaller record and a cheaper box test), chosen per
// child by a SAH cost model with one traversal cost per precision; a node whose
// two children are both narrow goes to the low-precision box pool
// (hw.box_low), any other to the full-precision one (hw.box).
//
// The cost model (vbsim's implementation of rtcore-systemc's marker,
// src/misc/mark.hpp): bottom-up, a leaf costs its triangle count in either
// precision; an interior node N, itself kept in precision P (its box B_P,
// B_low the box rounded outward), costs the sum over its children X of the
// cheaper of
//   t_trav_high + A(B_X) / A(N_P) * cost_high(X)
//   t_trav_low  + A(B_X,low) / A(N_P) * cost_low(X)
// (A: surface area, in double; a zero-area N_P counts each ratio as 1), and
// records the choice. Top-down from the root, kept in full precision, each
// child takes the choice its parent's precision made. Rounding outward keeps
// every box containing what it held, so a search finds the same hits and may
// only test more.
#pragma once
#include "scene/bvh.h"

namespace vbsim {

/// Marks `bvh`'s children by `marking` (precondition: marking.enabled; the
/// options checked by check_bvh_precision): rounds each low-precision child's
/// box in its parent's record and fills bvh.low_precision_node.
void mark_low_precision(Bvh& bvh, const BvhPrecisionMarking& marking);

/// Throws std::invalid_argument naming the field that is out of range.
void check_bvh_precision(const BvhPrecisionMarking& marking);

}  // namespace vbsim
