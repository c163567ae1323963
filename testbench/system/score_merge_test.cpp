// vbsim score --merge: the tables of runs over single families joined give the
// table of one run over all of them (only rays_per_s, a timing, differs).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

nlohmann::json rows_without_timing(const nlohmann::json& table) {
  nlohmann::json rows = table["rows"];
  for (auto& r : rows) r.erase("rays_per_s");
  return rows;
}

}  // namespace

TEST_CASE("score --merge of per-family tables equals one score of all families", "[cli][score]") {
  const auto dir = scratch_dir("score_merge");
  const std::string a = (dir / "crevice").string(), b = (dir / "corner").string();
  REQUIRE(run_vbsim("gen crevice --rays 6 -q -o " + a).exit_code == 0);
  REQUIRE(run_vbsim("gen corner --rays 6 -q -o " + b).exit_code == 0);
  const std::string opts = " -q --methods none,validity-bit,tmin:tmin-eps=1e-3 --testers three-half-plane";
  REQUIRE(run_vbsim("score " + a + " " + b + opts + " --out " + (dir / "all.json").string()).exit_code == 0);
  REQUIRE(run_vbsim("score " + a + opts + " --out " + (dir / "a.json").string()).exit_code == 0);
  REQUIRE(run_vbsim("score " + b + opts + " --out " + (dir / "b.json").string()).exit_code == 0);
  const SplitRun m = run_vbsim_split("score --merge " + (dir / "a.json").string() + " " + (dir / "b.json").string() +
                                     " --out " + (dir / "m.json").string() + " --accuracy-md " +
                                     (dir / "m.md").string());
  INFO(m.err);
  REQUIRE(m.exit_code == 0);
  CHECK_THAT(m.out, Catch::Contains("crevice") && Catch::Contains("corner"));  // the summary
  const auto all = nlohmann::json::parse(read_file(dir / "all.json"));
  const auto merged = nlohmann::json::parse(read_file(dir / "m.json"));
  CHECK(merged["families"] == all["families"]);
  CHECK(rows_without_timing(merged) == rows_without_timing(all));
  CHECK(merged["parts"].size() == 2);
  CHECK(read_file(dir / "m.md").find("| `validity-bit` |") != std::string::npos);

  // The same family twice, or different method lists, are refused by name.
  SplitRun bad = run_vbsim_split("score --merge " + (dir / "a.json").string() + " " + (dir / "a.json").string() +
                                 " --out " + (dir / "x.json").string());
  CHECK(bad.exit_code == 1);
  CHECK_THAT(bad.err, Catch::Contains("family 'crevice'"));
  REQUIRE(run_vbsim("score " + b + " -q --methods none --testers three-half-plane --out " + (dir / "c.json").string())
              .exit_code == 0);
  bad = run_vbsim_split("score --merge " + (dir / "a.json").string() + " " + (dir / "c.json").string() + " --out " +
                        (dir / "x.json").string());
  CHECK(bad.exit_code == 1);
  CHECK_THAT(bad.err, Catch::Contains("methods and testers differ"));
}
