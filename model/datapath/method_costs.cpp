// Operation counts per method; each count is derived in the comment beside it
// from the function that does the work (op_counts.h for the kinds).
#include "datapath/method_costs.h"

namespace vbsim {

using namespace ops;

namespace {

/// The candidate's geometric normal: 2 edges (6 fadd) and a cross product.
OpCounts triangle_normal() { return fadd(6) + cross(); }
/// unit_on_side (origin_offsets.cpp): normalize, dot with d, compare, 3 selects (19).
OpCounts unit_on_side() { return normalize() + dot() + fcmp(1) + fsel(3); }

}  // namespace

OpCounts emission_ops_for(const SelfIntersectionMethod& m, bool child, bool shadow) {
  OpCounts c;
  if (child && shadow && (m.shading_position || m.shading_position_always)) {
    // shading_position.cpp: per vertex normalize, p - v (3 fadd), dot, 3 fmul,
    // 3 fadd (24); the interpolation w = 1-u-v (2 fadd), 9 fmul + 6 fadd; the
    // convex-only test: 3 fadd, dot, compare, 3 selects (12).
    c += 3 * (normalize() + fadd(3) + dot() + fmul(3) + fadd(3)) + fadd(2) + fmul(9) + fadd(6);
    if (m.shading_position) c += fadd(3) + dot() + fcmp(1) + fsel(3);
  }
  if (child && m.offset_errbound) {
    // pbrt-v4 (pbrt_interaction.cpp; a step to the next float is a compare and
    // an integer step). The barycentrics are the renderer's own: recovering
    // them at replay is not the method's cost. A pbrt dot is fmul, 3 fma, fadd.
    const OpCounts pbrt_dot = fmul(1) + fma(3) + fadd(1);
    const OpCounts next_float = fcmp(1) + iadd(1);
    c += fmul(9) + fadd(6);                          // point b0 p0 + b1 p1 + b2 p2
    c += fsel(9) + fadd(6) + fmul(3);                // error: 9 abs, 6 adds, 3 products
    c += fcmp(3) + fadd(3 + 3) + 6 * next_float;     // interval: compares with 0, p -+ e, next floats
    c += fadd(3) + fdiv(3) + fadd(3) + fdiv(3);      // midpoint and half width
    c += fadd(6) + 3 * (fmul(1) + fma(2) + fadd(1))  // normal: edges, 3 differences of products,
         + fmul(3) + fadd(2) + fsqrt(1) + fdiv(3);   //   normalised
    c += fsel(3) + pbrt_dot;                         // dot(|n|, error)
    c += fmul(3);                                    // offset
    c += pbrt_dot + fcmp(1) + fsel(3);               // side: dot(w, n) < 0, 3 negations
    c += fadd(3);                                    // p + offset
    c += 3 * (fcmp(2) + next_float);                 // rounding outward
  }
  if (child && m.offset_adaptive) {
    // Listing 6-1: unit_on_side, then per component: fmul, float->int, sign
    // compare, negation select, integer add, abs, compare, fmul, fadd, select.
    c += unit_on_side() + 3 * (fmul(2) + cvt(1) + fcmp(2) + fsel(3) + iadd(1) + fadd(1));
  }
  if (child && m.offset_normal) c += unit_on_side() + fmul(3) + fadd(3);     // p + eps * u
  if (child && m.offset_direction) c += normalize() + fmul(3) + fadd(3);     // p + eps * unit(d)
  if (m.tmin) c += dot() + fsqrt(1) + fdiv(1);                               // |d| = sqrt(dot), eps / |d|
  if (shadow && m.reverse_shadow) c += fmul(3) + fadd(3) + fsel(3) + fsel(1); // o + t d, -d, sign flip
  if (child && m.validity_bit) c += dot() + fcmp(1);                         // sign = dot(d, Ng) < 0
  return c;
}

OpCounts result_ops_for(const SelfIntersectionMethod& m, bool shadow) {
  // reverse-shadow compares the parent's id with the closest hit once, when the
  // answer is concluded (functional_replayer.cpp, conclude_ray): the shader
  // that emitted the ray holds its parent, so the ray record carries no id.
  return shadow && m.reverse_shadow ? iadd(1) : OpCounts{};
}

namespace {

OpCounts suspect_ops(const AvoidanceConfig& a) {
  if (a.policy == AvoidancePolicy::SignOnly) return {};
  // epsilon (avoidance_unit.cpp, avoidance_epsilon): fixed is eps^2 (fmul);
  // exponent is 9 exponent extractions, 8 integer max, the guard band's
  // subtract and add (2), the max with the minimum, a shift, eps^2.
  OpCounts c = a.eps_mode == EpsilonMode::Fixed ? fmul(1) : ishift(9) + iadd(8 + 2 + 1) + ishift(1) + fmul(1);
  // normal test: candidate normal (15), o - v0 (3), dot, square, dot(Ng, Ng),
  // eps^2 * |Ng|^2, compare.
  if (a.test_normal) c += triangle_normal() + fadd(3) + dot() + fmul(1) + dot() + fmul(1) + fcmp(1);
  if (a.test_ray || a.test_component) c += fmul(3);  // t * d
  if (a.test_ray) c += dot() + fcmp(1);              // |t d|^2 < eps^2
  if (a.test_component) c += fmul(1) + fsel(3) + fcmp(3);  // scale * eps, 3 abs, 3 compares
  c += iadd(a.policy == AvoidancePolicy::Vote ? 6 : 2);   // combine the invalid bits
  return c;
}

}  // namespace

MethodOps method_ops(const SelfIntersectionMethod& m) {
  MethodOps o;
  o.emission = emission_ops_for(m, true, true);
  o.result = result_ops_for(m, true);
  // primid compares each candidate's id with the parent's (candidate_filter.cpp).
  if (m.primid) o.candidate += iadd(1);
  if (m.validity_bit) {
    o.candidate += iadd(1);  // sign bit == front/back bit
    o.suspect = suspect_ops(m.avoidance);
  }
  return o;
}

MethodCost method_cost(const SelfIntersectionMethod& m) {
  const MethodOps o = method_ops(m);
  return {o.emission.total(), o.result.total(), o.candidate.total(), o.suspect.total()};
}

}  // namespace vbsim
