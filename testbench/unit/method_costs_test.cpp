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
  CHECK(method_cost(parsed("tmin")).emission == 7);
  // unit normal on the leaving side: normalize 10, dot 5, compare 1, 3 selects;
  // then 3 mul + 3 add.
  CHECK(method_cost(parsed("offset-normal")).emission == 25);
  CHECK(method_cost(parsed("offset-direction")).emission == 16);
  // 19 for the unit normal, 10 per component.
  CHECK(method_cost(parsed("offset-adaptive")).emission == 49);
  const MethodCost composed = method_cost(parsed("offset-adaptive+primid"));
  CHECK(composed.emission == 49);
  CHECK(composed.candidate == 1);
  CHECK(composed.suspect == 0);
  CHECK(method_cost(parsed("offset-errbound")).emission > method_cost(parsed("offset-adaptive")).emission);
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
  vb.avoidance.eps_mode = EpsilonMode::Fixed;
  CHECK(method_cost(vb).suspect == 64 - 21);
  vb.avoidance.policy = AvoidancePolicy::Vote;
  CHECK(method_cost(vb).suspect == 64 - 21 + 4);
  const MethodCost sign_only = method_cost(parsed("sign-only"));
  CHECK(sign_only.candidate == 1);
  CHECK(sign_only.suspect == 0);
}
