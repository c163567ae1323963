// --method takes `vbsim score`'s METHOD:KEY=VALUE entries in replay and render,
// with the same effect as the long options.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "../unit/render_test_scene.h"
#include "run_vbsim.h"

using namespace vbsim::test;

TEST_CASE("render and replay take METHOD:KEY=VALUE like score", "[cli][render]") {
  const auto dir = scratch_dir("method_spec_options");
  write_render_test_obj((dir / "quad.obj").string());
  const std::string render = "render -q " + (dir / "quad.obj").string() + " --size 16x12 --light " +
                             kRenderTestLight + " -o " + (dir / "i.png").string();
  REQUIRE(run_vbsim(render + " -m validity-bit:vb-eps-mode=fixed:vb-eps=0.01 --stats " + (dir / "a.json").string())
              .exit_code == 0);
  REQUIRE(run_vbsim(render + " -m validity-bit --vb-eps-mode fixed --vb-eps 0.01 --stats " + (dir / "b.json").string())
              .exit_code == 0);
  auto a = nlohmann::json::parse(read_file(dir / "a.json")), b = nlohmann::json::parse(read_file(dir / "b.json"));
  CHECK(a["config"]["validity_bit"]["eps_mode"] == "fixed");
  CHECK(a["config"]["validity_bit"]["eps"] == b["config"]["validity_bit"]["eps"]);
  for (auto* j : {&a, &b}) {
    j->erase("sim");
    j->erase("provenance");
  }
  CHECK(a == b);
  // A long option given as well wins over the entry's key, as over a config file.
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  REQUIRE(run_vbsim("replay -q " + trace + " -m tmin:tmin-eps=0.5 --tmin-eps 0.001 --stats " +
                    (dir / "r.json").string())
              .exit_code == 0);
  CHECK(nlohmann::json::parse(read_file(dir / "r.json"))["config"]["tmin_eps"].get<double>() ==
        Approx(0.001));
  const SplitRun bad = run_vbsim_split("replay " + trace + " -m tmin:tmin-eps");
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Contains("'tmin-eps' is not KEY=VALUE"));
}
