// An independent float32 arithmetic for the reference-fidelity tests: every
// operation is carried out exactly in rationals (GMP) and rounded once to the
// nearest float, ties to even, by comparing the exact value with the candidate
// floats, so it shares no rounding code with the float operations and std::fma
// the production code relies on. Expected values of a reference's arithmetic
// (pbrt-v4, Ray Tracing Gems) are derived by replaying the reference's
// operations, in its order, through these functions.
#pragma once
#include <gmpxx.h>

#include <cfloat>
#include <cmath>
#include <cstdint>

#include "datapath/float_bits.h"
#include "datapath/vec3.h"
#include "exact/rational_rounding.h"

namespace vbsim::emu {

inline mpq_class exact(float f) {
  mpq_class q(static_cast<double>(f));  // a float is exact in double, and double in mpq
  return q;
}

/// q rounded to the nearest float (ties to even); beyond the float range, +-inf.
inline float round_float(const mpq_class& q) {
  if (q == 0) return 0.0f;
  // The nearest double is within half a double ulp; the nearest float is then
  // that double's float neighbour or one of the floats around it.
  const float guess = static_cast<float>(round_to_nearest_double(q));
  if (std::isinf(guess)) {
    const mpq_class top = exact(FLT_MAX) + mpq_class(std::ldexp(1.0, 127 - 24));  // FLT_MAX + half an ulp
    if (abs(q) < top) return q > 0 ? FLT_MAX : -FLT_MAX;
    return guess;
  }
  float best = guess;
  mpq_class best_err = abs(q - exact(guess));
  for (float c : {std::nextafter(guess, -INFINITY), std::nextafter(guess, INFINITY)}) {
    if (std::isinf(c)) continue;
    const mpq_class err = abs(q - exact(c));
    if (err < best_err) {
      best = c;
      best_err = err;
    } else if (err == best_err) {  // a tie: the float with an even significand
      if ((float_bits(c) & 1u) == 0) best = c;
    }
  }
  return best;
}

inline float add(float a, float b) { return round_float(exact(a) + exact(b)); }
inline float sub(float a, float b) { return round_float(exact(a) - exact(b)); }
inline float mul(float a, float b) {
  const float r = round_float(exact(a) * exact(b));
  return r == 0.0f && (std::signbit(a) != std::signbit(b)) ? -0.0f : r;
}
inline float div(float a, float b) { return round_float(exact(a) / exact(b)); }
inline float fma(float a, float b, float c) { return round_float(exact(a) * exact(b) + exact(c)); }
/// The double square root of a float, rounded to float, is the correctly rounded float square root.
inline float sqrt(float a) { return static_cast<float>(std::sqrt(static_cast<double>(a))); }

inline Vec3f sub(Vec3f a, Vec3f b) { return {sub(a.x, b.x), sub(a.y, b.y), sub(a.z, b.z)}; }

// pbrt-v4's operations, transcribed from its source onto the exact roundings.
inline float dop(float a, float b, float c, float d) {
  const float cd = mul(c, d);
  return add(fma(a, b, -cd), fma(-c, d, cd));
}
inline float sop(float a, float b, float c, float d) {
  const float cd = mul(c, d);
  return add(fma(a, b, cd), fma(c, d, -cd));
}
inline Vec3f cross(Vec3f a, Vec3f b) {
  return {dop(a.y, b.z, a.z, b.y), dop(a.z, b.x, a.x, b.z), dop(a.x, b.y, a.y, b.x)};
}
inline float dot(Vec3f a, Vec3f b) { return fma(a.x, b.x, sop(a.y, b.y, a.z, b.z)); }
inline Vec3f normalize(Vec3f a) {
  const float len = sqrt(add(add(mul(a.x, a.x), mul(a.y, a.y)), mul(a.z, a.z)));
  return {div(a.x, len), div(a.y, len), div(a.z, len)};
}
/// Plain float32 (no FMA) dot and cross, and normalisation by the reciprocal.
inline float plain_dot(Vec3f a, Vec3f b) { return add(add(mul(a.x, b.x), mul(a.y, b.y)), mul(a.z, b.z)); }
inline Vec3f plain_cross(Vec3f a, Vec3f b) {
  return {sub(mul(a.y, b.z), mul(a.z, b.y)), sub(mul(a.z, b.x), mul(a.x, b.z)), sub(mul(a.x, b.y), mul(a.y, b.x))};
}
inline Vec3f plain_normalize(Vec3f a) {
  const float inv = div(1.0f, sqrt(plain_dot(a, a)));
  return {mul(inv, a.x), mul(inv, a.y), mul(inv, a.z)};
}

}  // namespace vbsim::emu
