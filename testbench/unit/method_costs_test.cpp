// Operation counts of the methods, recounted by hand from the datapath's code.
#include <catch2/catch.hpp>

#include "datapath/method_costs.h"

using namespace vbsim;

namespace {
SelfIntersectionMethod parsed(const std::string& spec) {
  SelfIntersectionMethod m;
  std::string error;
  REQUIRE(parse_method(spec, m, error));
  return m;
}
}  // namespace

TEST_CASE("method costs: emission-time methods, counted by hand", "[method_costs]") {
  CHECK(method_cost(parsed("none")).emission == 0);
  // |d|: 3 mul, 2 add, sqrt; eps / |d|: 1 div.
  const OpCounts tmin = method_ops(parsed("tmin")).emission;
  CHECK(tmin.total() == 7);
  CHECK((tmin.fmul == 3 && tmin.fadd == 2 && tmin.fsqrt == 1 && tmin.fdiv == 1));
  // unit normal on the leaving side: normalize 10, dot 5, compare 1, 3 selects;
  // then 3 mul + 3 add.
  CHECK(method_cost(parsed("offset-normal")).emission == 25);
  CHECK(method_cost(parsed("offset-direction")).emission == 16);
  // 19 for the unit normal, 10 per component (of which one float->int conversion).
  CHECK(method_cost(parsed("offset-adaptive")).emission == 49);
  CHECK(method_ops(parsed("offset-adaptive")).emission.cvt == 3);
  const MethodCost composed = method_cost(parsed("offset-adaptive+primid"));
  CHECK(composed.emission == 49);
  CHECK(composed.candidate == 1);
  CHECK(composed.suspect == 0);
  // pbrt-v4's OffsetRayOrigin after its SurfaceInteraction: 23 fmul, 40 fadd,
  // 12 fma (the difference-of-products and pbrt's dots), 9 divides, 1 sqrt,
  // 15 abs/negations, 19 compares, 9 integer steps of next-float.
  const OpCounts eb = method_ops(parsed("offset-errbound")).emission;
  CHECK(eb.total() == 128);
  CHECK((eb.fmul == 23 && eb.fadd == 40 && eb.fma == 12 && eb.fdiv == 9 && eb.fsqrt == 1 && eb.fsel == 15 &&
         eb.fcmp == 19 && eb.iadd == 9));
  CHECK(method_cost(parsed("shading-position")).emission == 101);
  CHECK(method_cost(parsed("shading-position-always")).emission == 89);
}

TEST_CASE("method costs: each emission-time part acts on the rays ray emission gives it", "[method_costs]") {
  // ray_emission.cpp: tmin on every ray; offsets and the sign bit on rays with a
  // parent surface; shading positions on shadow rays with one; reverse-shadow on
  // every shadow ray.
  const SelfIntersectionMethod eb = parsed("offset-errbound+tmin");
  CHECK(emission_ops_for(eb, false, false).total() == 7);
  CHECK(emission_ops_for(eb, true, false).total() == 128 + 7);
  CHECK(emission_ops_for(parsed("validity-bit"), false, false).total() == 0);
  CHECK(emission_ops_for(parsed("validity-bit"), true, true).total() == 6);
  CHECK(emission_ops_for(parsed("shading-position"), true, false).total() == 0);
  CHECK(emission_ops_for(parsed("shading-position"), true, true).total() == 101);
  CHECK(emission_ops_for(parsed("reverse-shadow"), false, true).total() == 10);
  CHECK(emission_ops_for(parsed("reverse-shadow"), true, false).total() == 0);
  CHECK(result_ops_for(parsed("reverse-shadow"), true).total() == 1);
  CHECK(result_ops_for(parsed("reverse-shadow"), false).total() == 0);
}

TEST_CASE("method costs: reverse-shadow compares the parent id once per ray, not per candidate", "[method_costs]") {
  // conclude_ray compares the closest hit with the parent triangle once; the
  // id stays with the shader that emitted the ray, so the record is 259 bits.
  const SelfIntersectionMethod rs = parsed("reverse-shadow");
  const MethodCost c = method_cost(rs);
  CHECK(c.emission == 10);  // o + t d, -d, the sign flip
  CHECK(c.result == 1);
  CHECK(c.candidate == 0);
  CHECK(rs.bits_per_ray() == 259);
  // primid's comparison is per candidate, and its ray carries the id.
  CHECK(method_cost(parsed("primid")).candidate == 1);
  CHECK(parsed("primid").bits_per_ray() == 291);
}

TEST_CASE("method costs: the avoidance unit per candidate and per suspect", "[method_costs]") {
  SelfIntersectionMethod vb = parsed("validity-bit");
  vb.avoidance.eps_mode = EpsilonMode::Exponent;
  vb.avoidance.test_normal = vb.avoidance.test_ray = true;
  vb.avoidance.test_component = false;
  vb.avoidance.policy = AvoidancePolicy::All;
  MethodCost c = method_cost(vb);
  CHECK(c.emission == 6);   // the sign bit: dot, compare
  CHECK(c.candidate == 1);  // sign bit against the front/back bit
  // exponent epsilon 22; normal test 15 + 3 + 5 + 1 + 5 + 1 + 1 = 31; t d 3;
  // ray test 6; policy all 2.
  CHECK(c.suspect == 64);
  // By kind: 10 shifts/extractions, 11 + 2 integer ops; fmul 1 + 14 + 3 + 3;
  // fadd 16 + 2; compares 1 + 1.
  const OpCounts s = method_ops(vb).suspect;
  CHECK((s.ishift == 10 && s.iadd == 13 && s.fmul == 21 && s.fadd == 18 && s.fcmp == 2));
  vb.avoidance.eps_mode = EpsilonMode::Fixed;
  CHECK(method_cost(vb).suspect == 64 - 21);
  vb.avoidance.policy = AvoidancePolicy::Vote;
  CHECK(method_cost(vb).suspect == 64 - 21 + 4);
  vb.avoidance.test_component = true;  // scale * eps, 3 abs, 3 compares
  CHECK(method_cost(vb).suspect == 64 - 21 + 4 + 7);
  const MethodCost sign_only = method_cost(parsed("sign-only"));
  CHECK(sign_only.candidate == 1);
  CHECK(sign_only.suspect == 0);
}
