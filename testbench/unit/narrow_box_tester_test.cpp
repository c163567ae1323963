// The narrow box test (datapath/narrow_box_tester.h) against MPFR, the
// arithmetic rtcore-systemc's low-precision units compute in: every distance
// bit for bit on random rays and bounds (both signs, signed zeros, tiny and
// huge values, several widths); that it meets every box the exact slab test
// meets; and that a search whose low-precision nodes use it keeps its hits.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <mpfr.h>

#include "bench/functional_bench.h"
#include "datapath/bvh_stepper.h"
#include "datapath/closest_hit.h"
#include "datapath/narrow_box_tester.h"
#include "datapath/testers.h"
#include "scene/bvh.h"
#include "bvh_checks.h"

using namespace vbsim;

namespace {

/// One MPFR number of p bits, rounded and held to float32's exponent range
/// after every operation (MPFR exponent below -126: zero, above 128: infinity).
class Narrow {
 public:
  explicit Narrow(int p) { mpfr_init2(x_, p); }
  ~Narrow() { mpfr_clear(x_); }
  Narrow(const Narrow&) = delete;
  Narrow& operator=(const Narrow&) = delete;
  mpfr_t& get() { return x_; }
  void hold() {
    if (!mpfr_number_p(x_)) return;
    if (mpfr_get_exp(x_) < -126) mpfr_set_zero(x_, mpfr_signbit(x_) ? -1 : 1);
    else if (mpfr_get_exp(x_) > 128) mpfr_set_inf(x_, mpfr_signbit(x_) ? -1 : 1);
  }
  void set(double v, mpfr_rnd_t r) {
    mpfr_set_d(x_, v, r);
    hold();
  }
  double value() const { return mpfr_get_d(x_, MPFR_RNDN); }

 private:
  mpfr_t x_;
};

/// rtcore's low-precision slab distance of bound `b` on one axis: the bound,
/// its difference with the origin and the quotient by the direction, each
/// rounded so that a near distance only shrinks and a far one only grows
/// (the origin and direction are rounded once each way).
double mpfr_distance(double b, double o, double d, int p, bool far) {
  Narrow o_down(p), o_up(p), d_down(p), d_up(p), t(p);
  o_down.set(o, MPFR_RNDD);
  o_up.set(o, MPFR_RNDU);
  d_down.set(d, MPFR_RNDD);
  d_up.set(d, MPFR_RNDU);
  const bool negative = std::signbit(d);
  // Directions of the three roundings, and which rounded origin and direction.
  const bool up_bound = negative ? !far : far;
  mpfr_rnd_t r_bound = up_bound ? MPFR_RNDU : MPFR_RNDD;
  mpfr_rnd_t r_div = far ? MPFR_RNDU : MPFR_RNDD;
  Narrow& origin = up_bound ? o_down : o_up;
  Narrow& direction = up_bound ? d_down : d_up;
  t.set(b, r_bound);
  mpfr_sub(t.get(), t.get(), origin.get(), r_bound);
  t.hold();
  mpfr_div(t.get(), t.get(), direction.get(), r_div);
  t.hold();
  return t.value();
}

bool same(float a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return static_cast<double>(a) == b && std::signbit(a) == std::signbit(b);
}

float pick(std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> kind(0, 9), exponent(-140, 127);
  switch (kind(rng)) {
    case 0: return 0.0f;
    case 1: return -0.0f;
    case 2: return std::ldexp(unit(rng), exponent(rng));  // anywhere in float32's range, tiny to huge
    default: return 100.0f * unit(rng);
  }
}

}  // namespace

TEST_CASE("narrow slab distances equal MPFR's, rounding by rounding", "[narrow-box]") {
  std::mt19937 rng(17);
  uint64_t compared = 0, infinite = 0;
  for (int bits : {7, 0, 3, 10, 22}) {
    for (int i = 0; i < 20000; ++i) {
      Ray ray;
      ray.o = {pick(rng), pick(rng), pick(rng)};
      ray.d = {pick(rng), pick(rng), pick(rng)};
      const NarrowBoxTester narrow(ray, bits);
      const float bound = pick(rng);
      for (int axis = 0; axis < 3; ++axis)
        for (bool far : {false, true}) {
          const float got = narrow.distance(axis, bound, far);
          const double want = mpfr_distance(bound, ray.o[axis], ray.d[axis], bits + 1, far);
          INFO("bits " << bits << " bound " << bound << " o " << ray.o[axis] << " d " << ray.d[axis] << " far " << far);
          REQUIRE(same(got, want));
          ++compared;
          infinite += std::isinf(want);
        }
    }
  }
  CHECK(compared == 5 * 20000 * 6);
  CHECK(infinite > 1000);  // zero directions and huge quotients were covered
}

TEST_CASE("the narrow test meets every box the exact slab test meets", "[narrow-box]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  uint64_t exact_met = 0, narrow_only = 0;
  for (int i = 0; i < 50000; ++i) {
    Ray ray;
    ray.o = {u(rng), u(rng), u(rng)};
    ray.d = {u(rng), u(rng), u(rng)};
    Bounds3f b;
    for (int a = 0; a < 3; ++a) {
      const float x = u(rng), y = u(rng);
      b.lo[a] = std::min(x, y);
      b.hi[a] = std::max(x, y);
    }
    // The exact slab test, in rationals' stead long double over float inputs:
    // every difference and quotient below is exact to far more than float32.
    long double tn = ray.tmin, tf = std::numeric_limits<long double>::infinity();
    for (int a = 0; a < 3; ++a) {
      const long double t0 = ((long double)b.lo[a] - ray.o[a]) / ray.d[a];
      const long double t1 = ((long double)b.hi[a] - ray.o[a]) / ray.d[a];
      tn = std::max(tn, std::min(t0, t1));
      tf = std::min(tf, std::max(t0, t1));
    }
    const bool exact = tn * (1 + 1e-12L) < tf;  // clearly met (a margin for the long double rounding)
    float entry = 0;
    const bool narrow = NarrowBoxTester(ray, 7).hits(b, INFINITY, entry);
    if (exact) {
      ++exact_met;
      REQUIRE(narrow);
      CHECK(entry <= tn);
    }
    narrow_only += narrow && !(tn <= tf);
  }
  CHECK(exact_met > 5000);
  CHECK(narrow_only > 0);  // and it meets more
}

TEST_CASE("a search whose low-precision nodes are tested narrow keeps its hits, with more work", "[narrow-box]") {
  const Scene bunny = load_scene(test::kBunnyPath);
  BvhBuildOptions o;
  o.low_precision.enabled = true;
  const Bvh rounded = build_bvh(bunny, o);
  o.low_precision.narrow_arithmetic = true;
  const Bvh narrow = build_bvh(bunny, o);
  REQUIRE(narrow.narrow_mantissa_bits == 7);
  REQUIRE(rounded.narrow_mantissa_bits == -1);
  const std::vector<TraceRay> rays = bench_rays(bunny, 4000, 9);
  const CandidateFilter filter(SelfIntersectionMethod{});
  BvhStepper<ThreeHalfPlaneTester> stepper(narrow, filter, 4);
  TraversalCounters total_rounded, total_narrow;
  uint64_t hits = 0;
  for (const TraceRay& tr : rays) {
    Ray ray;
    ray.o = tr.o;
    ray.d = tr.d;
    CandidateCounters c1, c2, c3;
    TraversalCounters t1, t2, t3;
    const Hit a = closest_hit<ThreeHalfPlaneTester>(rounded, ray, filter, c1, t1);
    const Hit b = closest_hit<ThreeHalfPlaneTester>(narrow, ray, filter, c2, t2);
    REQUIRE(a.prim == b.prim);
    REQUIRE(a.t == b.t);
    // The stepper over the narrow tree: the same hit and the same work.
    StepRequest q = stepper.begin(ray, false, c3, t3);
    while (q.kind != StepRequest::Done) {
      if (q.kind == StepRequest::Node) q = stepper.node_step();
      else if (q.kind == StepRequest::Refill) q = stepper.refilled();
      else {
        for (uint32_t i = q.index; i < q.index + q.count; ++i) stepper.triangle_step(i);
        q = stepper.leaf_done();
      }
    }
    REQUIRE(stepper.hit().prim == b.prim);
    REQUIRE(t3.node_visits == t2.node_visits);
    REQUIRE(t3.triangle_tests == t2.triangle_tests);
    total_rounded.add(t1);
    total_narrow.add(t2);
    hits += b.prim >= 0;
  }
  CHECK(hits > 1000);
  CHECK(total_narrow.node_visits > total_rounded.node_visits);  // the narrow test meets more boxes
}
