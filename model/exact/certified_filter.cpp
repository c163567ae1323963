// Error analysis (u = 2^-53, round to nearest, no FMA: the build uses -ffp-contract=off).
//
// Model. For doubles x, y and op in {+, -, *, /}: fl(x op y) = (x op y)(1 + a),
// |a| <= u, and also (x op y) = fl(x op y)(1 + b), |b| <= u (Higham, ASNA (2.4),
// (2.5)); a sum or difference that underflows is exact; a product or quotient
// that underflows is off by at most 2^-1075 absolute.
//
// Inputs. The exact origin o* is rational; o = its double rounding, rd >= |o* - o|
// (measured exactly per ray). Vertices and d are doubles (floats), exact.
//   A = fl(v0 - o) approximates A* = v0 - o*:  |A - A*| <= u|A| + rd  =: eA.
//   E01 = fl(v1 - v0) approximates v1 - v0:    |E01 - E01*| <= u|E01| =: eE01.
//
// Quantities. With Ng = (v1 - v0) x (v2 - v0) = E20* x E01*:
//   e0 = det(d, A*, E01*) = d . ((v0 - o*) x (v1 - o*)), and cyclically e1, e2;
//   den = e0 + e1 + e2 = d . Ng;   N = det(A*, E20*, E01*) = (v0 - o*) . Ng;  t = N / den.
//
// Bound on det. Let perm(a, b, c) = sum over cyclic (i, j, k) of a_i (b_j c_k + b_k c_j),
// so |det(a, b, c)| <= perm(|a|, |b|, |c|). For doubles X, Y, Z approximating
// X*, Y*, Z* within eX, eY, eZ, the value v = fl(X . (Y x Z)) (evaluated as in
// det_bounded) satisfies
//   |v - det(X*, Y*, Z*)| <= g5 perm(|X|,|Y|,|Z|)              rounding: every product
//                                                             X_i Y_j Z_k passes <= 5 roundings
//                          + perm(eX, |Y|+eY, |Z|+eZ)          telescoping det(X*,Y*,Z*) -
//                          + perm(|X|, eY, |Z|+eZ)             det(X,Y,Z) one argument at a
//                          + perm(|X|, |Y|, eZ)                time (det is multilinear)
//                          + eta
// with g5 = 5u/(1-5u) < 6u. The bound itself is a polynomial with nonnegative
// coefficients in nonnegative doubles (|X|, rd, ...), evaluated with at most 11
// roundings on any path (e: 1, |Z|+e: 1, perm: 5, times g5: 1, sum of perms: 3),
// so its true value is at most the computed value times (1-u)^-11 < 1 + 12u;
// multiplying by kSlack = 1 + 2^-48 = 1 + 32u covers that and the rounding of
// the product itself (adding eta afterwards loses at most u(bound + eta)).
// eta = 2^-900 covers underflow: with |o| <= 2^130 every factor is below 2^132,
// so the 2^-1075 absolute error of an underflowing product grows to less than
// 2^-930 in total, in the value and in the bound. Magnitudes stay below
// 2^(3 * 132), so nothing overflows.
// When |v| > bound, sign(v) = sign(det(X*, Y*, Z*)).
//
// Decisions. Edge signs certain and mixed: miss. All three certain and equal:
// den has that sign and |den| = sum |e_k| lies in [sum(|v_k| - err_k),
// sum(|v_k| + err_k)]; with N's sign certain, t lies in [N_lo / den_hi,
// N_hi / den_lo]. Each end is a handful of roundings (<= 4) away from its exact
// value, and is pushed outward by the factor 1 -+ 2^-48 (>= 32u); an end that
// may have underflowed is replaced by 0 (lower) or raised by eta (upper).
#include "exact/certified_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "exact/rational_rounding.h"

namespace vbsim {

namespace {

constexpr double kU = 0x1p-53;
constexpr double kGamma5 = 6 * kU;
constexpr double kSlack = 1 + 0x1p-48;      // >= 1 + 32u, see the header comment
constexpr double kSlackDown = 1 - 0x1p-48;  // for lower bounds after <= 4 roundings
constexpr double kEta = 0x1p-900;
constexpr double kTiny = 0x1p-800;  // below this a bound's own underflow could matter
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Bounded {
  double v;    // computed value
  double err;  // proven bound on |v - exact|
};

double perm(const double a[3], const double b[3], const double c[3]) {
  return a[0] * (b[1] * c[2] + b[2] * c[1]) + a[1] * (b[2] * c[0] + b[0] * c[2]) +
         a[2] * (b[0] * c[1] + b[1] * c[0]);
}

// det(X, Y, Z) = X . (Y x Z) with the bound of the header comment. eX may be
// null (X exact, as d is).
Bounded det_bounded(const double X[3], const double* eX, const double Y[3], const double eY[3],
                    const double Z[3], const double eZ[3]) {
  const double c0 = Y[1] * Z[2] - Y[2] * Z[1];
  const double c1 = Y[2] * Z[0] - Y[0] * Z[2];
  const double c2 = Y[0] * Z[1] - Y[1] * Z[0];
  const double v = (X[0] * c0 + X[1] * c1) + X[2] * c2;
  double aX[3], aY[3], aZ[3], hY[3], hZ[3];
  for (int i = 0; i < 3; ++i) {
    aX[i] = std::fabs(X[i]);
    aY[i] = std::fabs(Y[i]);
    aZ[i] = std::fabs(Z[i]);
    hY[i] = aY[i] + eY[i];
    hZ[i] = aZ[i] + eZ[i];
  }
  double err = kGamma5 * perm(aX, aY, aZ) + perm(aX, eY, hZ) + perm(aX, aY, eZ);
  if (eX) err += perm(eX, hY, hZ);
  return {v, err * kSlack + kEta};
}

int certain_sign(const Bounded& b) {
  if (b.v > b.err) return 1;
  if (b.v < -b.err) return -1;
  return 0;
}

// Lower/upper bounds of x, given that the exact quantity is within 2.01u|x| +
// 2^-1075 of the double x (two roundings, possibly one underflow). The margin
// 2^-50|x| + 2^-1073 exceeds that plus the rounding of the widening itself.
double widen_down(double x) {
  return std::isfinite(x) ? x - std::fabs(x) * 0x1p-50 - 0x1p-1073 : x;
}
double widen_up(double x) { return std::isfinite(x) ? x + std::fabs(x) * 0x1p-50 + 0x1p-1073 : x; }

}  // namespace

FilterRay make_filter_ray(const ExactRay& ray) {
  FilterRay r;
  const mpq_class* eo[3] = {&ray.o.x, &ray.o.y, &ray.o.z};
  const mpq_class* ed[3] = {&ray.d.x, &ray.d.y, &ray.d.z};
  bool usable = true;
  for (int i = 0; i < 3; ++i) {
    r.o[i] = eo[i]->get_d();
    if (!std::isfinite(r.o[i]) || std::fabs(r.o[i]) > 0x1p130) usable = false;
    const mpq_class err = *eo[i] - r.o[i];
    r.rd[i] = round_up_double(abs(err));
    if (r.rd[i] == 0) {
      r.o_lo[i] = r.o_hi[i] = r.o[i];
    } else {  // one rounding of the sum, then one ulp outward
      r.o_lo[i] = std::nextafter(r.o[i] - r.rd[i], -kInf);
      r.o_hi[i] = std::nextafter(r.o[i] + r.rd[i], kInf);
    }
    r.d[i] = ed[i]->get_d();
    const double ad = std::fabs(r.d[i]);
    if (cmp(*ed[i], r.d[i]) != 0 || ad > 0x1p128 || (ad != 0 && ad < 0x1p-160)) usable = false;
  }
  if (ray.has_tmax) {
    r.tmax_lo = round_down_double(ray.tmax);
    r.tmax_hi = round_up_double(ray.tmax);
  } else {
    r.tmax_lo = r.tmax_hi = kInf;
  }
  r.usable = usable;
  return r;
}

FilterVerdict filter_triangle(const FilterRay& r, const Triangle& tri, double& t_lo, double& t_hi) {
  const Vec3f* v[3] = {&tri.v0, &tri.v1, &tri.v2};
  double P[3][3], eP[3][3];  // P[k] = v_k - o (A, B, C)
  double E[3][3], eE[3][3];  // E[k] = v_{k+1} - v_k (E01, E12, E20)
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 3; ++i) {
      const double a = (*v[k])[i], b = (*v[(k + 1) % 3])[i];
      P[k][i] = a - r.o[i];
      eP[k][i] = kU * std::fabs(P[k][i]) + r.rd[i];
      E[k][i] = b - a;
      eE[k][i] = kU * std::fabs(E[k][i]);
    }
  }
  Bounded e[3];
  int pos = 0, neg = 0;
  for (int k = 0; k < 3; ++k) {
    e[k] = det_bounded(r.d, nullptr, P[k], eP[k], E[k], eE[k]);
    const int s = certain_sign(e[k]);
    pos += s > 0;
    neg += s < 0;
  }
  if (pos && neg) return FilterVerdict::Miss;
  if (pos != 3 && neg != 3) return FilterVerdict::Unknown;
  const int den_sign = pos == 3 ? 1 : -1;
  // |den| = sum |e_k| exactly (all share one sign); each |e_k| in [|v| - err, |v| + err].
  const double den_lo =
      ((std::fabs(e[0].v) - e[0].err) + (std::fabs(e[1].v) - e[1].err) + (std::fabs(e[2].v) - e[2].err)) *
      kSlackDown;
  const double den_hi =
      ((std::fabs(e[0].v) + e[0].err) + (std::fabs(e[1].v) + e[1].err) + (std::fabs(e[2].v) + e[2].err)) *
          kSlack + kEta;
  if (!(den_lo > kTiny)) return FilterVerdict::PlaneOnly;
  const Bounded n = det_bounded(P[0], eP[0], E[2], eE[2], E[0], eE[0]);
  const int n_sign = certain_sign(n);
  if (n_sign == 0) return FilterVerdict::PlaneOnly;
  if (n_sign != den_sign) return FilterVerdict::Miss;  // t < 0
  const double n_lo = std::fabs(n.v) - n.err;  // > 0, one rounding
  const double n_hi = std::fabs(n.v) + n.err;
  t_lo = n_lo / den_hi * kSlackDown;
  if (t_lo < kTiny) t_lo = 0;  // the quotient may have underflowed; 0 < t anyway
  t_hi = n_hi / den_lo * kSlack + kEta;
  if (t_lo >= r.tmax_hi) return FilterVerdict::Miss;
  if (!(t_hi < r.tmax_lo)) return FilterVerdict::PlaneOnly;
  return FilterVerdict::Hit;
}

// Slab test on the origin enclosure [o_lo, o_hi]: for d_i > 0 the entry
// (lo_i - o*_i) / d_i is at least (lo_i - o_hi_i) / d_i and the exit at most
// (hi_i - o_lo_i) / d_i (mirrored for d_i < 0); each is one subtraction and one
// division, widened outward. With |o| <= 2^130 and |d_i| >= 2^-160 nothing
// overflows. For d_i = 0 the ray's coordinate is constant and must lie in the slab.
bool filter_box(const FilterRay& r, const float lo[3], const float hi[3], double t_limit,
                double& t_near) {
  double tn = 0, tf = t_limit;
  for (int i = 0; i < 3; ++i) {
    const double l = lo[i], h = hi[i];
    if (r.d[i] == 0) {
      if (r.o_hi[i] < l || r.o_lo[i] > h) return false;
      continue;
    }
    double a, b;
    if (r.d[i] > 0) {
      a = widen_down((l - r.o_hi[i]) / r.d[i]);
      b = widen_up((h - r.o_lo[i]) / r.d[i]);
    } else {
      a = widen_down((h - r.o_lo[i]) / r.d[i]);
      b = widen_up((l - r.o_hi[i]) / r.d[i]);
    }
    if (a > tn) tn = a;
    if (b < tf) tf = b;
  }
  if (tn > tf) return false;
  t_near = tn;
  return true;
}

}  // namespace vbsim
