// Method list entries of `vbsim score`: names, parameters, errors.
#include <catch2/catch.hpp>

#include "replay/replay_config.h"
#include "score/method_spec.h"

using namespace vbsim;

TEST_CASE("a method entry sets the named parameters and keeps the other defaults", "[score][method-spec]") {
  const MethodSpec s = parse_method_spec("validity-bit:vb-eps-mode=fixed:vb-eps=2.5e-3:vb-policy=vote");
  CHECK(s.label == "validity-bit:vb-eps-mode=fixed:vb-eps=2.5e-3:vb-policy=vote");
  const SelfIntersectionMethod& m = s.options.method;
  CHECK(m.validity_bit);
  CHECK_FALSE(m.tmin);
  CHECK(m.avoidance.eps_mode == EpsilonMode::Fixed);
  CHECK(m.avoidance.eps == 2.5e-3f);
  CHECK(m.avoidance.policy == AvoidancePolicy::Vote);
  CHECK(m.avoidance.guard_bits == AvoidanceConfig{}.guard_bits);

  const MethodSpec t = parse_method_spec("offset-adaptive+primid:adaptive-int-scale=512:vb-tests=normal+component");
  CHECK(t.options.method.offset_adaptive);
  CHECK(t.options.method.primid);
  CHECK(t.options.method.adaptive.int_scale == 512.0f);
  CHECK_FALSE(t.options.method.avoidance.test_ray);
  CHECK(t.options.method.avoidance.test_component);

  const MethodSpec h = parse_method_spec("none:hitpoint=barycentric:vb-guard-bits=3");
  CHECK(h.options.hit_point == HitPointMode::Barycentric);
  CHECK(h.options.method.avoidance.guard_bits == 3);
}

TEST_CASE("a method list splits on commas", "[score][method-spec]") {
  const auto list = parse_method_list("none,tmin:tmin-eps=1e-3,sign-only");
  REQUIRE(list.size() == 3);
  CHECK(list[1].options.method.tmin_eps == 1e-3f);
  CHECK(list[2].options.method.avoidance.policy == AvoidancePolicy::SignOnly);
  for (const std::string& entry : default_score_methods()) CHECK_NOTHROW(parse_method_spec(entry));
}

TEST_CASE("bad method entries name the entry and the problem", "[score][method-spec]") {
  auto message = [](const std::string& entry) {
    try {
      parse_method_list(entry);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(message("tmin:eps=1"), Catch::Contains("'tmin:eps=1'") && Catch::Contains("unknown key 'eps'"));
  CHECK_THAT(message("tmin:tmin-eps=abc"), Catch::Contains("not a number"));
  CHECK_THAT(message("tmin:tmin-eps=-1"), Catch::Contains("tmin_eps") && Catch::Contains(">= 0"));
  CHECK_THAT(message("validity-bit:vb-guard-bits=2.5"), Catch::Contains("not an integer"));
  CHECK_THAT(message("validity-bit:vb-policy=most"), Catch::Contains("validity_bit.policy"));
  CHECK_THAT(message("validity-bit:vb-tests=normal+side"), Catch::Contains("unknown test 'side'"));
  CHECK_THAT(message("tmin:tmin-eps"), Catch::Contains("not KEY=VALUE"));
  CHECK_THAT(message("warp"), Catch::Contains("unknown value"));
  CHECK_THAT(message("none,,tmin"), Catch::Contains("empty entry"));
  CHECK_THAT(message(":tmin-eps=1"), Catch::Contains("no method name"));
}
