// Reduced precision: float32 values rounded to fewer mantissa bits, as a
// narrower datapath would hold them. `bits` is the number of stored fraction
// bits kept (0 .. 23; 23 leaves a float unchanged); the exponent keeps its
// float32 range. Infinities and NaNs pass unchanged.
//
//   round_down / round_up   toward -inf / +inf (directed: a box rounded with
//                           them, lo down and hi up, contains the original)
//   round_nearest           to nearest, ties to even
//
// A box unit that holds node bounds rounded outward can only meet more boxes
// than the full-precision one, so a closest-hit search over it stays exact (it
// visits a superset of the subtrees); a triangle tester on rounded vertices
// moves the triangles and so changes hits.
#pragma once
#include <cmath>
#include <cstdint>

#include "datapath/float_bits.h"
#include "datapath/triangle.h"
#include "scene/bvh.h"
#include "scene/scene.h"

namespace vbsim {

namespace reduced_precision_detail {

inline uint32_t dropped_mask(int bits) {
  const int drop = 23 - (bits < 0 ? 0 : bits > 23 ? 23 : bits);
  return (uint32_t{1} << drop) - 1u;
}

/// |x| rounded toward zero (away: false) or away from zero (true), sign kept.
inline float round_magnitude(float x, int bits, bool away) {
  if (!std::isfinite(x)) return x;
  const uint32_t mask = dropped_mask(bits);
  const uint32_t u = float_bits(x);
  if ((u & mask) == 0u) return x;  // already representable
  return bits_float(away ? (u | mask) + 1u : u & ~mask);  // a carry moves into the exponent
}

}  // namespace reduced_precision_detail

/// The largest value with `bits` fraction bits that is <= x.
inline float round_down(float x, int bits) {
  return reduced_precision_detail::round_magnitude(x, bits, std::signbit(x));
}

/// The smallest value with `bits` fraction bits that is >= x.
inline float round_up(float x, int bits) {
  return reduced_precision_detail::round_magnitude(x, bits, !std::signbit(x));
}

/// x rounded to the nearest value with `bits` fraction bits (ties to even).
inline float round_nearest(float x, int bits) {
  if (!std::isfinite(x)) return x;
  const uint32_t mask = reduced_precision_detail::dropped_mask(bits);
  if (mask == 0u) return x;
  const uint32_t u = float_bits(x);
  const uint32_t lsb = (u & (mask + 1u)) != 0u ? 1u : 0u;  // the lowest kept bit, for ties to even
  return bits_float((u + (mask >> 1) + lsb) & ~mask);
}

/// `b` with every low bound rounded down and every high bound up: contains `b`.
inline Bounds3f round_outward(const Bounds3f& b, int bits) {
  Bounds3f r;
  for (int a = 0; a < 3; ++a) {
    r.lo[a] = round_down(b.lo[a], bits);
    r.hi[a] = round_up(b.hi[a], bits);
  }
  return r;
}

/// Node `n` with both children's boxes rounded outward (its references kept).
inline BvhNode round_outward(const BvhNode& n, int bits) {
  BvhNode r = n;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 2; ++c) {
      r.box[a][0][c] = round_down(n.box[a][0][c], bits);
      r.box[a][1][c] = round_up(n.box[a][1][c], bits);
    }
  return r;
}

/// Wide node `n` with every used slot's box rounded outward (its references kept).
template <int W>
WideBvhNode<W> round_outward(const WideBvhNode<W>& n, int bits) {
  WideBvhNode<W> r = n;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < static_cast<int>(n.children); ++c) {
      r.box[a][0][c] = round_down(n.box[a][0][c], bits);
      r.box[a][1][c] = round_up(n.box[a][1][c], bits);
    }
  return r;
}

/// Every coordinate of `v` rounded to nearest.
inline Vec3f round_nearest(const Vec3f& v, int bits) {
  return {round_nearest(v.x, bits), round_nearest(v.y, bits), round_nearest(v.z, bits)};
}

/// `t` with every vertex coordinate rounded to nearest.
inline Triangle round_nearest(const Triangle& t, int bits) {
  return {round_nearest(t.v0, bits), round_nearest(t.v1, bits), round_nearest(t.v2, bits)};
}

}  // namespace vbsim
