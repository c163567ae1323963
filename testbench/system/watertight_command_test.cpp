// vbsim watertight on a mesh of the user's own, with JSON output.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

TEST_CASE("watertight measures a given mesh, open ones at their interior, and writes JSON", "[cli][tester]") {
  const auto dir = scratch_dir("watertight_mesh");
  // A unit square of two triangles: one interior edge (the diagonal), no interior vertex.
  write_file(dir / "square.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
  const std::string json = (dir / "w.json").string();
  const SplitRun r = run_vbsim_split("watertight " + (dir / "square.obj").string() +
                                     " --testers three-half-plane,pbrt-watertight --outside 3 --inside 0 --json " + json);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("| three-half-plane |") && Catch::Contains("4 boundary edges"));
  const auto j = nlohmann::json::parse(read_file(json));
  CHECK(j["origins"]["outside"] == 3);
  REQUIRE(j["rows"].size() == 2);
  for (const auto& row : j["rows"]) {
    CHECK(row["triangles"] == 2);
    CHECK(row["open_edges"] == 4);
    CHECK(row["rays"].get<int>() + row["skipped"].get<int>() == 3 * 3);  // 3 targets on the diagonal x 3 origins
    CHECK(row["lost"] == 0);
  }
  CHECK(j["rows"][1]["tester"] == "pbrt-watertight");
  CHECK(j["provenance"]["inputs"][0]["path"] == (dir / "square.obj").string());
  const SplitRun bad = run_vbsim_split("watertight --outside 2");
  CHECK(bad.exit_code == 2);
  const SplitRun missing = run_vbsim_split("watertight /no/such.obj");
  CHECK(missing.exit_code == 1);
}
