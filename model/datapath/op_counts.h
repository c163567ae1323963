// OpCounts: the arithmetic of one datapath step (a box test, a triangle test,
// an avoidance-unit test, an emission-time method, a stack push or pop), by
// kind of operator, as counted from the code that does it. The kinds are the
// rows of the technology file (docs/energy.md), which prices each one in
// energy and area:
//   fadd   float add or subtract        fmul   float multiply
//   fma    fused multiply-add           fdiv   float divide (or reciprocal)
//   fsqrt  float square root            fcmp   float compare, min or max
//   fsel   float abs, negation or select (a sign-bit or multiplexer operation)
//   iadd   integer add, compare, max, or a compare of ids or bits
//   ishift integer shift or exponent-field extraction
//   cvt    float <-> integer conversion
// Vector helpers count per component: dot = 3 fmul + 2 fadd, cross = 6 fmul +
// 3 fadd, normalize = dot + fsqrt + fdiv + 3 fmul.
#pragma once
#include <cstdint>

namespace vbsim {

struct OpCounts {
  int fadd = 0, fmul = 0, fma = 0, fdiv = 0, fsqrt = 0, fcmp = 0, fsel = 0, iadd = 0, ishift = 0, cvt = 0;

  int total() const { return fadd + fmul + fma + fdiv + fsqrt + fcmp + fsel + iadd + ishift + cvt; }

  OpCounts& operator+=(const OpCounts& o) {
    fadd += o.fadd, fmul += o.fmul, fma += o.fma, fdiv += o.fdiv, fsqrt += o.fsqrt;
    fcmp += o.fcmp, fsel += o.fsel, iadd += o.iadd, ishift += o.ishift, cvt += o.cvt;
    return *this;
  }
  friend OpCounts operator+(OpCounts a, const OpCounts& b) { return a += b; }
  friend OpCounts operator*(int k, OpCounts a) {
    a.fadd *= k, a.fmul *= k, a.fma *= k, a.fdiv *= k, a.fsqrt *= k;
    a.fcmp *= k, a.fsel *= k, a.iadd *= k, a.ishift *= k, a.cvt *= k;
    return a;
  }
  friend bool operator==(const OpCounts& a, const OpCounts& b) {
    return a.fadd == b.fadd && a.fmul == b.fmul && a.fma == b.fma && a.fdiv == b.fdiv && a.fsqrt == b.fsqrt &&
           a.fcmp == b.fcmp && a.fsel == b.fsel && a.iadd == b.iadd && a.ishift == b.ishift && a.cvt == b.cvt;
  }
};

/// Named constructors, so a count reads as what it is: ops::fadd(3) + ops::fmul(6).
namespace ops {
inline OpCounts fadd(int n) { OpCounts c; c.fadd = n; return c; }
inline OpCounts fmul(int n) { OpCounts c; c.fmul = n; return c; }
inline OpCounts fma(int n) { OpCounts c; c.fma = n; return c; }
inline OpCounts fdiv(int n) { OpCounts c; c.fdiv = n; return c; }
inline OpCounts fsqrt(int n) { OpCounts c; c.fsqrt = n; return c; }
inline OpCounts fcmp(int n) { OpCounts c; c.fcmp = n; return c; }
inline OpCounts fsel(int n) { OpCounts c; c.fsel = n; return c; }
inline OpCounts iadd(int n) { OpCounts c; c.iadd = n; return c; }
inline OpCounts ishift(int n) { OpCounts c; c.ishift = n; return c; }
inline OpCounts cvt(int n) { OpCounts c; c.cvt = n; return c; }
/// 3 fmul + 2 fadd.
inline OpCounts dot() { return fmul(3) + fadd(2); }
/// 6 fmul + 3 fadd.
inline OpCounts cross() { return fmul(6) + fadd(3); }
/// dot + sqrt + divide + 3 fmul (10).
inline OpCounts normalize() { return dot() + fsqrt(1) + fdiv(1) + fmul(3); }
}  // namespace ops

}  // namespace vbsim
