// The failure scenarios' expectations agree with a brute-force rational
// closest hit over every triangle (oracle_test_support.h, Cramer's rule, no
// BVH), and their traces carry the parent data the methods need.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>

#include "exact/expected_answers.h"
#include "gen/scenario.h"
#include "oracle_test_support.h"

using namespace vbsim;

namespace {

void check_case(const ScenarioCase& c) {
  INFO("case " << c.name);
  const Scene scene = make_scene(c.triangles);
  const Bvh bvh = build_bvh(scene);
  std::vector<TraceRay> rays = c.rays;
  fill_expect(rays, scene, bvh);
  const ParentRays parents = collect_parent_rays(rays);
  std::map<int64_t, size_t> index;
  size_t children = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const TraceRay& r = rays[i];
    INFO("ray " << r.id);
    index[r.id] = i;
    if (r.parent >= 0) {
      ++children;
      REQUIRE(index.count(r.parent) == 1);  // the parent came before
      CHECK(r.parent_prim >= 0);
      CHECK(r.has_parent_t);
      CHECK(r.has_parent_uv);
      CHECK(r.sign >= 0);
    }
    if (i % 3 != 0) continue;  // a sample: every third ray
    const ExactRay intended = intended_ray(r, scene, find_parent(parents, r.parent));
    const test::ReferenceClosest ref = test::reference_closest(scene, intended);
    if (ref.ties.empty()) {
      CHECK(r.expect_prim == -1);
    } else {
      CHECK(std::find(ref.ties.begin(), ref.ties.end(), r.expect_prim) != ref.ties.end());
    }
  }
  CHECK(children > 0);
}

void check_scenario(const std::string& name, std::map<std::string, std::string> values) {
  const Scenario* s = find_scenario(name);
  REQUIRE(s != nullptr);
  const ScenarioSettings settings(4, 9, std::move(values));
  for (const ScenarioCase& c : s->generate(settings)) check_case(c);
}

}  // namespace

TEST_CASE("failure scenario expectations agree with brute-force rational closest hits", "[gen][scenarios][oracle]") {
  check_scenario("random-triangles", {});
  check_scenario("random-triangles", {{"protocol", "pbrt"}});
  check_scenario("grazing", {{"hitpoint", "ray"}});
  check_scenario("shared-edges", {});
  check_scenario("crevice", {});
  check_scenario("corner", {});
}

TEST_CASE("failure scenarios name a bad setting", "[gen][scenarios]") {
  const auto gen = [](const std::string& name, std::map<std::string, std::string> v) {
    ScenarioSettings s(4, 1, std::move(v));
    find_scenario(name)->generate(s);
  };
  CHECK_THROWS_WITH(gen("random-triangles", {{"protocol", "x"}}), Catch::Contains("protocol=x"));
  CHECK_THROWS_WITH(gen("grazing", {{"surfaces", "plane,,bowl"}}), Catch::Contains("surfaces"));
  CHECK_THROWS_WITH(gen("grazing", {{"surfaces", "cone"}}), Catch::Contains("cone"));
  CHECK_THROWS_WITH(gen("shared-edges", {{"grid", "7"}}), Catch::Contains("grid=7"));
  CHECK_THROWS_WITH(gen("crevice", {{"angles", "1,200"}}), Catch::Contains("200"));
  CHECK_THROWS_WITH(gen("corner", {{"gap_max", "5"}}), Catch::Contains("gap_max"));
  CHECK_THROWS_WITH(gen("grazing", {{"hitpoint", "given"}}), Catch::Contains("hitpoint=given"));
}
