// RayBoxTester: the robust slab test (Ize 2013) of the closest-hit search, for
// the root's box, for both child boxes of a BvhNode at once, and for every
// slot of a 4- or 8-wide node (WideBvhNode) at once. The far
// distance is widened by 1 + 2 gamma(3) so that float rounding never culls a box
// the ray touches; a zero direction component is replaced by +-1e-18 (as Embree
// does), so no slab distance is ever NaN.
//
// Every distance is ((bound - o) * (1 / d)) in float32, the entry the max of the
// three near distances and tmin, the exit the min of the three far distances
// times the widening; a box is met when entry <= min(exit, tmax). The two-child
// test has an SSE2 form (both children in two lanes) and a scalar form; they
// round identically, so which one runs never changes a search.
#pragma once
#include <cstddef>
#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "datapath/ray.h"
#include "scene/bvh.h"

namespace vbsim {

/// Whether the host runs AVX2 (RayBoxTester::hits_avx2), asked once.
inline bool host_has_avx2() {
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return has;
#else
  return false;
#endif
}

/// Slab tests of one ray (latched at construction) against the root box and node child boxes.
class RayBoxTester {
 public:
  /// Far distances are widened by 1 + 2 gamma(3), gamma(n) = n u / (1 - n u), u = 2^-24.
  static constexpr float kWiden = 1.0f + 2.0f * (3.0f * 5.9604645e-8f) / (1.0f - 3.0f * 5.9604645e-8f);

  /// 1 / d, with |d| < 1e-18 replaced by 1e-18 of d's sign.
  static float safe_reciprocal(float d) {
    constexpr float tiny = 1e-18f;
    return 1.0f / (std::fabs(d) < tiny ? std::copysign(tiny, d) : d);
  }

  /// Per-ray set-up (as a hardware box unit latches the ray: o, 1/d, tmin).
  explicit RayBoxTester(const Ray& ray) : tmin_(ray.tmin) {  // (the vectors are set below)
#if defined(__SSE2__)
    {  // safe_reciprocal of the three components in one vector division (the same roundings)
      const __m128 d = _mm_setr_ps(ray.d.x, ray.d.y, ray.d.z, 1.0f);
      const __m128 sign = _mm_set1_ps(-0.0f), tiny = _mm_set1_ps(1e-18f);
      const __m128 small = _mm_cmplt_ps(_mm_andnot_ps(sign, d), tiny);
      const __m128 safe = _mm_or_ps(_mm_andnot_ps(small, d), _mm_and_ps(small, _mm_or_ps(tiny, _mm_and_ps(sign, d))));
      alignas(16) float inv[4];
      _mm_store_ps(inv, _mm_div_ps(_mm_set1_ps(1.0f), safe));
      for (int a = 0; a < 3; ++a) inv_[a] = inv[a];
    }
#else
    for (int a = 0; a < 3; ++a) inv_[a] = safe_reciprocal(ray.d[a]);
#endif
    for (int a = 0; a < 3; ++a) {
      o_[a] = ray.o[a];
      // The sign of 1/d is d's own (safe_reciprocal keeps it; -0 gives -1/tiny):
      // taken from d, the node offsets need not wait for the division.
      near_side_[a] = std::signbit(ray.d[a]) ? 1 : 0;
      near_pair_[a] = 4 * a + 2 * near_side_[a];
      far_pair_[a] = 4 * a + 2 * (1 - near_side_[a]);
      wide_near_[a] = static_cast<ptrdiff_t>(sizeof(float) * 4 * (2 * a + near_side_[a]));
      wide_far_[a] = static_cast<ptrdiff_t>(sizeof(float) * 4 * (2 * a + 1 - near_side_[a]));
    }
#if defined(__SSE2__)
    o_xy_ = _mm_setr_ps(o_[0], o_[0], o_[1], o_[1]);
    inv_xy_ = _mm_setr_ps(inv_[0], inv_[0], inv_[1], inv_[1]);
    o_z_ = _mm_set1_ps(o_[2]);
    inv_z_ = _mm_set1_ps(inv_[2]);
    tmin4_ = _mm_set1_ps(ray.tmin);
    for (int a = 0; a < 3; ++a) {
      o_lanes_[a] = _mm_set1_ps(o_[a]);
      inv_lanes_[a] = _mm_set1_ps(inv_[a]);
    }
#endif
  }

  /// The latched 1 / d on `axis` (safe_reciprocal of the ray's component).
  float reciprocal(int axis) const { return inv_[axis]; }

  /// True when the ray's interval [tmin, tmax] meets box `b`.
  bool hits(const Bounds3f& b, float tmax) const {
    const float bound[2][3] = {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}};  // [side][axis]
    float tn = tmin_, tf = INFINITY;
    for (int a = 0; a < 3; ++a) {
      tn = std::max(tn, (bound[near_side_[a]][a] - o_[a]) * inv_[a]);
      tf = std::min(tf, (bound[1 - near_side_[a]][a] - o_[a]) * inv_[a]);
    }
    return tn <= std::min(tf * kWiden, tmax);
  }

#if defined(__SSE2__)
  /// hits(b, tmax) with the three axes in one SSE2 vector (the wide searches'
  /// root test): the same products, and the same maxima and minima, as no
  /// distance is NaN (1/d finite and non-zero, o and b finite), so the same answer.
  bool hits_sse2(const Bounds3f& b, float tmax) const {
    static_assert(sizeof(Bounds3f) == 6 * sizeof(float), "Bounds3f is lo then hi, three floats each");
    const float* const f = &b.lo.x;
    const __m128 lo = _mm_loadu_ps(f);                                   // lo.x lo.y lo.z hi.x
    const __m128 tail = _mm_loadu_ps(f + 2);                             // lo.z hi.x hi.y hi.z
    const __m128 hi = _mm_shuffle_ps(tail, tail, _MM_SHUFFLE(3, 3, 2, 1));  // hi.x hi.y hi.z hi.z
    const __m128 o = _mm_setr_ps(o_[0], o_[1], o_[2], o_[2]);
    const __m128 inv = _mm_setr_ps(inv_[0], inv_[1], inv_[2], inv_[2]);
    const __m128 back = _mm_cmplt_ps(inv, _mm_setzero_ps());  // near side: hi where 1/d < 0
    const __m128 near = _mm_or_ps(_mm_and_ps(back, hi), _mm_andnot_ps(back, lo));
    const __m128 far = _mm_or_ps(_mm_andnot_ps(back, hi), _mm_and_ps(back, lo));
    const __m128 tn = _mm_mul_ps(_mm_sub_ps(near, o), inv), tf = _mm_mul_ps(_mm_sub_ps(far, o), inv);
    const __m128 tn_max = _mm_max_ss(_mm_max_ss(_mm_max_ss(_mm_set_ss(tmin_), tn), _mm_shuffle_ps(tn, tn, 1)),
                                     _mm_movehl_ps(tn, tn));
    const __m128 tf_min = _mm_min_ss(_mm_min_ss(tf, _mm_shuffle_ps(tf, tf, 1)), _mm_movehl_ps(tf, tf));
    const __m128 limit = _mm_min_ss(_mm_mul_ss(tf_min, _mm_set_ss(kWiden)), _mm_set_ss(tmax));
    return _mm_cvtss_f32(tn_max) <= _mm_cvtss_f32(limit);
  }
#endif

  /// Tests both child boxes of `n` against [tmin, tmax]: bit c of the result is
  /// set when child c's box is met, and entry_c is where the ray enters that
  /// box (clamped to tmin; meaningful only when bit c is set).
  unsigned hits(const BvhNode& n, float tmax, float& entry0, float& entry1) const {
#if defined(__SSE2__)
    return hits_sse2(n, tmax, entry0, entry1);
#else
    return hits_scalar(n, tmax, entry0, entry1);
#endif
  }

  /// The two-child test in plain float arithmetic (the reference form).
  unsigned hits_scalar(const BvhNode& n, float tmax, float& entry0, float& entry1) const {
    unsigned mask = 0;
    float* const entry[2] = {&entry0, &entry1};
    for (int c = 0; c < 2; ++c) {
      float tn = tmin_, tf = INFINITY;
      for (int a = 0; a < 3; ++a) {
        tn = std::max(tn, (n.box[a][near_side_[a]][c] - o_[a]) * inv_[a]);
        tf = std::min(tf, (n.box[a][1 - near_side_[a]][c] - o_[a]) * inv_[a]);
      }
      *entry[c] = tn;
      mask |= static_cast<unsigned>(tn <= std::min(tf * kWiden, tmax)) << c;
    }
    return mask;
  }

#if defined(__SSE2__)
  /// The two-child test with SSE2: lanes 0 and 1 are children 0 and 1.
  unsigned hits_sse2(const BvhNode& n, float tmax, float& entry0, float& entry1) const {
    const float* b = &n.box[0][0][0];
    // The 8-byte pair of both children's bounds that starts at float `at`, into
    // the low or the high half of a vector.
    const auto low = [b](int at) { return _mm_load_sd(reinterpret_cast<const double*>(b + at)); };
    const auto high = [b](__m128d v, int at) { return _mm_loadh_pd(v, reinterpret_cast<const double*>(b + at)); };
    // Lanes: near (far) x of children 0, 1, then near (far) y of children 0, 1;
    // and near z of children 0, 1, then far z of children 0, 1.
    const __m128 near_xy = _mm_castpd_ps(high(low(near_pair_[0]), near_pair_[1]));
    const __m128 far_xy = _mm_castpd_ps(high(low(far_pair_[0]), far_pair_[1]));
    const __m128 z = _mm_castpd_ps(high(low(near_pair_[2]), far_pair_[2]));
    const __m128 tn_xy = _mm_mul_ps(_mm_sub_ps(near_xy, o_xy_), inv_xy_);
    const __m128 tf_xy = _mm_mul_ps(_mm_sub_ps(far_xy, o_xy_), inv_xy_);
    const __m128 t_z = _mm_mul_ps(_mm_sub_ps(z, o_z_), inv_z_);
    const __m128 tn = _mm_max_ps(_mm_max_ps(tn_xy, _mm_movehl_ps(tn_xy, tn_xy)), _mm_max_ps(t_z, tmin4_));
    const __m128 tf = _mm_min_ps(_mm_min_ps(tf_xy, _mm_movehl_ps(tf_xy, tf_xy)), _mm_movehl_ps(t_z, t_z));
    const __m128 limit = _mm_min_ps(_mm_mul_ps(tf, _mm_set1_ps(kWiden)), _mm_set1_ps(tmax));
    entry0 = _mm_cvtss_f32(tn);
    entry1 = _mm_cvtss_f32(_mm_shuffle_ps(tn, tn, 1));
    return static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(tn, limit))) & 3u;
  }
#endif

  /// Tests the used slots of wide node `n` against [tmin, tmax]: bit c of the
  /// result is set when slot c's box is met, entry[c] where the ray enters it
  /// (clamped to tmin; written for every slot, meaningful only when bit c is
  /// set); no bit at or above n.children is ever set. The same arithmetic as
  /// the two-child test, box by box.
  template <int W>
  unsigned hits(const WideBvhNode<W>& n, float tmax, float* entry) const {
#if defined(__SSE2__)
    return hits_wide_sse2(n, tmax, entry);
#else
    return hits_wide_scalar(n, tmax, entry);
#endif
  }

  /// The wide test in plain float arithmetic (the reference form).
  template <int W>
  unsigned hits_wide_scalar(const WideBvhNode<W>& n, float tmax, float* entry) const {
    unsigned mask = 0;
    for (int c = 0; c < W; ++c) {
      float tn = tmin_, tf = INFINITY;
      for (int a = 0; a < 3; ++a) {
        tn = std::max(tn, (n.box[a][near_side_[a]][c] - o_[a]) * inv_[a]);
        tf = std::min(tf, (n.box[a][1 - near_side_[a]][c] - o_[a]) * inv_[a]);
      }
      entry[c] = tn;
      mask |= static_cast<unsigned>(tn <= std::min(tf * kWiden, tmax)) << c;
    }
    return mask & ((1u << n.children) - 1u);
  }

#if defined(__SSE2__)
  /// The wide test with SSE2, four slots a vector. Each axis's near and far
  /// rows are read at the byte offsets the constructor chose by the sign of
  /// 1/d (wide_near_ / wide_far_). The maxima and minima are taken as a tree
  /// and "entry <= min(exit * widen, tmax)" as two comparisons, for a shorter
  /// dependency chain: no used slot's distance is NaN (1/d is finite and
  /// non-zero, the origin finite), so these are the scalar form's values (a
  /// zero's sign aside, which no comparison sees) and the same mask. Slots at
  /// or above n.children are not masked off here, as the scalar form does:
  /// they hold inverted boxes (WideBvhNode::clear), whose entry is +inf (NaN
  /// for an infinite origin) and whose exit is -inf (or NaN) whatever the ray,
  /// so neither comparison passes (one step less on each node step's chain).
  template <int W>
  unsigned hits_wide_sse2(const WideBvhNode<W>& n, float tmax, float* entry) const {
    constexpr int kScale = W / 4;  // a W-wide node's rows are kScale times a 4-wide node's
    const __m128 widen = _mm_set1_ps(kWiden), limit_t = _mm_set1_ps(tmax);
    const char* const rows = reinterpret_cast<const char*>(&n.box[0][0][0]);
    const auto row = [rows](ptrdiff_t offset4, int g) {
      return _mm_load_ps(reinterpret_cast<const float*>(rows + offset4 * kScale) + g);
    };
    unsigned mask = 0;
    for (int g = 0; g < W; g += 4) {
      __m128 tn_a[3], tf_a[3];
      for (int a = 0; a < 3; ++a) {
        tn_a[a] = _mm_mul_ps(_mm_sub_ps(row(wide_near_[a], g), o_lanes_[a]), inv_lanes_[a]);
        tf_a[a] = _mm_mul_ps(_mm_sub_ps(row(wide_far_[a], g), o_lanes_[a]), inv_lanes_[a]);
      }
      const __m128 tn = _mm_max_ps(_mm_max_ps(tmin4_, tn_a[0]), _mm_max_ps(tn_a[1], tn_a[2]));
      const __m128 tf = _mm_min_ps(tf_a[0], _mm_min_ps(tf_a[1], tf_a[2]));
      _mm_storeu_ps(entry + g, tn);
      const __m128 met = _mm_and_ps(_mm_cmple_ps(tn, _mm_mul_ps(tf, widen)), _mm_cmple_ps(tn, limit_t));
      mask |= static_cast<unsigned>(_mm_movemask_ps(met)) << g;
    }
    return mask;
  }
#endif

#if defined(__x86_64__) && defined(__GNUC__)
  /// The 8-wide test in one AVX2 vector (the same arithmetic, lane for lane,
  /// as hits_wide_sse2; no FMA, so nothing is contracted). Only on a host with AVX2
  /// (host_has_avx2()); the searches choose it once per ray.
  __attribute__((target("avx2"))) unsigned hits_avx2(const WideBvhNode<8>& n, float tmax,
                                                                      float* entry) const {
    const char* const rows = reinterpret_cast<const char*>(&n.box[0][0][0]);
    __m256 tn_a[3], tf_a[3];
    for (int a = 0; a < 3; ++a) {  // an 8-wide node's rows are twice a 4-wide node's
      const __m256 o = _mm256_set1_ps(o_[a]), inv = _mm256_set1_ps(inv_[a]);
      const __m256 near = _mm256_load_ps(reinterpret_cast<const float*>(rows + 2 * wide_near_[a]));
      const __m256 far = _mm256_load_ps(reinterpret_cast<const float*>(rows + 2 * wide_far_[a]));
      tn_a[a] = _mm256_mul_ps(_mm256_sub_ps(near, o), inv);
      tf_a[a] = _mm256_mul_ps(_mm256_sub_ps(far, o), inv);
    }
    const __m256 tn = _mm256_max_ps(_mm256_max_ps(_mm256_set1_ps(tmin_), tn_a[0]), _mm256_max_ps(tn_a[1], tn_a[2]));
    const __m256 tf = _mm256_min_ps(tf_a[0], _mm256_min_ps(tf_a[1], tf_a[2]));
    _mm256_storeu_ps(entry, tn);
    const __m256 met = _mm256_and_ps(_mm256_cmp_ps(tn, _mm256_mul_ps(tf, _mm256_set1_ps(kWiden)), _CMP_LE_OQ),
                                     _mm256_cmp_ps(tn, _mm256_set1_ps(tmax), _CMP_LE_OQ));
    return static_cast<unsigned>(_mm256_movemask_ps(met));  // unused slots never met (hits_wide_sse2)
  }
#endif

  /// Host bytes from the tester's start that the two-child test reads (a
  /// timing model may prefetch them before a step).
  static constexpr size_t two_child_host_bytes() { return offsetof(RayBoxTester, tmin_); }

 private:
  // What the two-child test uses first (a search interleaved with many others
  // finds it in as few host cache lines as possible), then the scalar forms' state.
#if defined(__SSE2__)
  __m128 o_xy_, inv_xy_, o_z_, inv_z_;  ///< lanes as hits_sse2 lays them out
  __m128 tmin4_;                        ///< the ray's tmin in every lane
#endif
  int near_pair_[3];  ///< per axis: float offset in BvhNode::box of both children's near bounds
  int far_pair_[3];   ///< ... and of their far bounds
  float tmin_;
  float o_[3];
  float inv_[3];
  int near_side_[3];  ///< per axis: 0 (low bound) when the reciprocal is >= 0, else 1
#if defined(__SSE2__)
  __m128 o_lanes_[3], inv_lanes_[3];    ///< per axis: o and 1/d in every lane (the wide test)
#endif
  /// Per axis: byte offset in a 4-wide node's boxes of the slots' near (far)
  /// bounds; twice that in an 8-wide node (WideBvhNode's box[axis][side][slot]).
  ptrdiff_t wide_near_[3], wide_far_[3];
};

}  // namespace vbsim
