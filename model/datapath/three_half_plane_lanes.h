// ThreeHalfPlaneTester::intersect_lanes: the three-half-plane test of four
// triangles of a leaf at once, from the tree's TriangleLanes. Inline (a
// search's leaf step takes it in, and the AVX2 search compiles it for AVX2:
// the same operations, the same bits).
#pragma once
#include <cstddef>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "datapath/testers.h"
#include "scene/triangle_lanes.h"

namespace vbsim {

#if defined(__SSE2__)
// The same steps as intersect(), lane for lane, up to its division: every
// product, difference and sum in the same order, compared the same way (no FMA
// on the project's x86-64 baseline, so nothing is contracted in either form).
// The division and the checks on its quotient are LaneHits::below's.
inline void ThreeHalfPlaneTester::intersect_lanes(const TriangleLanes& lanes, uint32_t first, int n, float bound,
                                           LaneHits& out) const {
  const float o[3] = {o_.x, o_.y, o_.z};
  const __m128 ox = _mm_set1_ps(o[kx_]), oy = _mm_set1_ps(o[ky_]), oz = _mm_set1_ps(o[kz_]);
  const __m128 sx = _mm_set1_ps(sx_), sy = _mm_set1_ps(sy_), sz = _mm_set1_ps(sz_);
  // Coordinate kx (ky, kz) of vertex v of the four triangles: at px (py, pz) + v * vs.
  const float* const base = lanes.coord(0, 0) + first;
  const size_t as = lanes.axis_stride(), vs = lanes.vertex_stride();
  const float* const px = base + static_cast<size_t>(kx_) * as;
  const float* const py = base + static_cast<size_t>(ky_) * as;
  const float* const pz = base + static_cast<size_t>(kz_) * as;
  const auto rel = [](const float* p, __m128 o) { return _mm_sub_ps(_mm_loadu_ps(p), o); };
  // Vertices relative to the origin, then sheared: (x, y) in the plane across d, z along it.
  const __m128 a_z = rel(pz, oz), b_z = rel(pz + vs, oz), c_z = rel(pz + 2 * vs, oz);
  const __m128 ax = _mm_sub_ps(rel(px, ox), _mm_mul_ps(sx, a_z));
  const __m128 ay = _mm_sub_ps(rel(py, oy), _mm_mul_ps(sy, a_z));
  const __m128 bx = _mm_sub_ps(rel(px + vs, ox), _mm_mul_ps(sx, b_z));
  const __m128 by = _mm_sub_ps(rel(py + vs, oy), _mm_mul_ps(sy, b_z));
  const __m128 cx = _mm_sub_ps(rel(px + 2 * vs, ox), _mm_mul_ps(sx, c_z));
  const __m128 cy = _mm_sub_ps(rel(py + 2 * vs, oy), _mm_mul_ps(sy, c_z));
  const __m128 e_u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
  const __m128 e_v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
  const __m128 e_w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));

  const __m128 zero = _mm_setzero_ps();
  const unsigned used = (1u << n) - 1u;
  const __m128 any_zero = _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(e_u, zero), _mm_cmpeq_ps(e_v, zero)), _mm_cmpeq_ps(e_w, zero));
  const __m128 any_neg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(e_u, zero), _mm_cmplt_ps(e_v, zero)), _mm_cmplt_ps(e_w, zero));
  const __m128 any_pos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(e_u, zero), _mm_cmpgt_ps(e_v, zero)), _mm_cmpgt_ps(e_w, zero));
  const __m128 det = _mm_add_ps(_mm_add_ps(e_u, e_v), e_w);
  const __m128 t_scaled =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(e_u, _mm_mul_ps(sz, a_z)), _mm_mul_ps(e_v, _mm_mul_ps(sz, b_z))),
                 _mm_mul_ps(e_w, _mm_mul_ps(sz, c_z)));
  const __m128 sign = _mm_set1_ps(-0.0f);
  const __m128 abs_det = _mm_andnot_ps(sign, det);
  const __m128 t_signed = _mm_xor_ps(t_scaled, _mm_and_ps(_mm_cmplt_ps(det, zero), sign));
  const __m128 tmin = _mm_set1_ps(tmin_), upper = _mm_set1_ps(bound);
  __m128 ok = _mm_andnot_ps(_mm_and_ps(any_neg, any_pos), _mm_cmpneq_ps(det, zero));
  ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpgt_ps(t_signed, _mm_mul_ps(tmin, abs_det)),
                                 _mm_cmplt_ps(t_signed, _mm_mul_ps(upper, abs_det))));

  out.redo = static_cast<unsigned>(_mm_movemask_ps(any_zero)) & used;
  out.met = static_cast<unsigned>(_mm_movemask_ps(ok)) & used & ~out.redo;
  out.tmin = tmin_;
  _mm_store_ps(out.t_scaled, t_scaled);
  _mm_store_ps(out.e_v, e_v);
  _mm_store_ps(out.e_w, e_w);
  _mm_store_ps(out.det, det);
}
#endif

}  // namespace vbsim
