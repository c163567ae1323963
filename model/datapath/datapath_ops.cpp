// Operation counts of the traversal datapath, each derived beside the code it
// counts (op_counts.h for the kinds).
#include "datapath/datapath_ops.h"

namespace vbsim {

using namespace ops;

OpCounts box_test_ops() {
  // ray_box_tester.h, hits(): per axis (bound - o) * inv for the near and the
  // far bound (2 fadd, 2 fmul), the near distance into a max (with tmin: 3
  // max), the far ones into a min (2 min); tf * kWiden (fmul), min with tmax,
  // entry <= limit (2 fcmp).
  return fadd(6) + fmul(6) + fcmp(3 + 2) + fmul(1) + fcmp(2);
}

OpCounts box_setup_ops() {
  // RayBoxTester(ray): per axis safe_reciprocal (|d| and copysign: 2 fsel; the
  // compare with 1e-18; 1 / d) and the near side (inv >= 0).
  return 3 * (fsel(2) + fcmp(1) + fdiv(1) + fcmp(1));
}

namespace {

OpCounts three_half_plane_test() {
  // three_half_plane_tester.cpp, intersect():
  return fadd(9)                    // a, b, c = v - o
         + fmul(6) + fadd(6)        // ax .. cy = a[kx] - sx * a[kz] ...
         + fmul(6) + fadd(3)        // e_u, e_v, e_w (2 products, a difference each)
         + fcmp(3)                  // any edge function exactly 0
         + fcmp(6)                  // mixed signs: three < 0, three > 0
         + fadd(2) + fcmp(1)        // det = e_u + e_v + e_w, det == 0
         + fmul(3)                  // az, bz, cz
         + fmul(3) + fadd(2)        // t_scaled
         + fsel(1)                  // |det|
         + fcmp(1) + fsel(1)        // t_signed: det < 0, conditional negation
         + fmul(2) + fcmp(2)        // tmin |det| < t_signed < tmax |det|
         + fdiv(1) + fcmp(2)        // t = t_scaled / det, tmin < t < tmax
         + fdiv(2)                  // u, v
         + fcmp(1);                 // front = det > 0
}

OpCounts moller_trumbore_test() {
  // moller_trumbore_tester.cpp, intersect():
  return fadd(6)                       // e1, e2
         + cross()                     // p = d x e2
         + dot() + fcmp(1) + fdiv(1)   // det, det == 0, 1 / det
         + fadd(3)                     // s = o - v0
         + dot() + fmul(1) + fcmp(2)   // u and its bounds
         + cross()                     // q = s x e1
         + dot() + fmul(1) + fcmp(1) + fadd(1) + fcmp(1)  // v >= 0, u + v <= 1
         + dot() + fmul(1) + fcmp(2)   // t, tmin < t < tmax
         + fcmp(1);                    // front = det > 0
}

OpCounts pbrt_watertight_test() {
  // pbrt_float.h: difference_of_products = fmul + 2 fma + fadd; pbrt_cross = 3 of them.
  const OpCounts dop = fmul(1) + fma(2) + fadd(1);
  // max_abs3: 3 abs, 2 max.
  const OpCounts max_abs3 = fsel(3) + fcmp(2);
  // pbrt_watertight_tester.cpp, intersect_triangle() then intersect():
  return fadd(6) + 3 * dop                 // degenerate: pbrt_cross(v2 - v0, v1 - v0)
         + fmul(3) + fadd(2) + fcmp(1)     // its squared length == 0
         + fadd(9)                         // q = v - o
         + fmul(6) + fadd(6)               // shear: p.x += sx * p.z ...
         + 3 * dop                         // e0, e1, e2
         + fcmp(3) + fcmp(6)               // any exactly 0; mixed signs
         + fadd(2) + fcmp(1)               // det, det == 0
         + fmul(3)                         // p.z *= sz
         + fmul(3) + fadd(2)               // t_scaled
         + fmul(1) + fcmp(6)               // tmax * det; det's sign, t_scaled's sign and bound
         + fdiv(1) + fmul(1)               // inv_det, t
         + max_abs3 + fmul(1)              // max_zt, delta_z
         + 2 * max_abs3                    // max_xt, max_yt
         + 2 * (fadd(1) + fmul(1))         // delta_x, delta_y
         + fmul(5) + fadd(2)               // delta_e
         + max_abs3                        // max_e
         + fmul(6) + fadd(2) + fsel(1)     // delta_t (|inv_det|)
         + fcmp(1)                         // t > delta_t
         + fmul(3)                         // b0, b1, b2
         + iadd(1)                         // front = (det > 0) == dz_negative
         + fcmp(2);                        // intersect(): tmin < t < tmax
}

}  // namespace

OpCounts triangle_test_ops(TesterKind kind) {
  switch (kind) {
    case TesterKind::MollerTrumbore: return moller_trumbore_test();
    case TesterKind::PbrtWatertight: return pbrt_watertight_test();
    default: return three_half_plane_test();
  }
}

OpCounts triangle_test_critical_path(TesterKind kind) {
  // Independent operations run side by side (a pipelined datapath has one
  // operator per counted operation); a compare of two bounds, or of three
  // values, is one stage; the double-precision redo is an exception path, off
  // the chain.
  switch (kind) {
    case TesterKind::MollerTrumbore:
      // e2 = v2 - v0 (fadd); p = d x e2 (fmul, fadd); det = dot(e1, p) (fmul,
      // fadd, fadd); 1 / det (fdiv); v = dot(d, q) * inv_det (fmul; q = s x e1
      // and its dot are ready long before); u + v (fadd); u + v <= 1 (fcmp).
      // (t = dot(e2, q) * inv_det and its compare run beside v's.)
      return fadd(1) + fmul(1) + fadd(1) + fmul(1) + fadd(2) + fdiv(1) + fmul(1) + fadd(1) + fcmp(1);
    case TesterKind::PbrtWatertight:
      // q = v - o (fadd); shear p.x += sx * p.z (fmul, fadd); e0..e2 =
      // difference_of_products (fmul, then fma, then the error's fadd); det =
      // e0 + e1 + e2 (fadd, fadd); inv_det = 1 / det (fdiv); delta_t's last
      // factor |inv_det| (fsel) and product (fmul; the rest of the bound is
      // ready before inv_det, and t = t_scaled * inv_det runs beside it);
      // t > delta_t, with tmin < t < tmax beside it (fcmp).
      return fadd(1) + fmul(1) + fadd(1) + fmul(1) + fma(1) + fadd(1) + fadd(2) + fdiv(1) + fsel(1) + fmul(1) +
             fcmp(1);
    default:
      // three_half_plane_tester.cpp: a = v - o (fadd); shear a[kx] - sx *
      // a[kz] (fmul, fadd); edge function cx * by - cy * bx (fmul, fadd);
      // t_scaled = e_u az + e_v bz + e_w cz (fmul, fadd, fadd; det's two fadds
      // and the scaled range test run beside it); t = t_scaled / det (fdiv);
      // tmin < t < tmax (fcmp).
      return fadd(1) + fmul(1) + fadd(1) + fmul(1) + fadd(1) + fmul(1) + fadd(2) + fdiv(1) + fcmp(1);
  }
}

OpCounts triangle_setup_ops(TesterKind kind) {
  // max_dimension(d): 3 abs, 2 compares.
  const OpCounts max_dimension = fsel(3) + fcmp(2);
  switch (kind) {
    case TesterKind::MollerTrumbore: return {};  // latches o, d, tmin only
    case TesterKind::PbrtWatertight:
      // sx = -d[kx] / d[kz], sy likewise (2 fdiv, 2 negations), sz = 1 / d[kz], d[kz] < 0.
      return max_dimension + fdiv(2) + fsel(2) + fdiv(1) + fcmp(1);
    default:
      // d[kz] < 0 (the swap), sx, sy, sz.
      return max_dimension + fcmp(1) + fdiv(3);
  }
}

OpCounts stack_push_ops() {
  // bvh_stepper.h, node_step(): sp += 1, onchip == depth (the spill test),
  // onchip += 1; the entry's 96 bits are written (kStackEntryBits, priced as
  // register bits).
  return iadd(3);
}

OpCounts stack_pop_ops() {
  // bvh_stepper.h, pop(): the sp == 0 and onchip == 0 tests, --sp, --onchip,
  // and the entry's distance against tmax (the entry's 96 bits are read).
  return iadd(4) + fcmp(1);
}

}  // namespace vbsim
