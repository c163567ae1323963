// vbsim gen into an existing directory: it replaces the files an earlier gen
// wrote there, and refuses trace files it did not write (score would read them).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;
namespace fs = std::filesystem;

TEST_CASE("gen into its own earlier directory leaves no stale file", "[cli][gen]") {
  const auto dir = scratch_dir("gen_again");
  const std::string out = (dir / "g").string();
  // crevice writes one case per angle: four, then one.
  REQUIRE(run_vbsim("gen crevice --rays 4 -q -o " + out).exit_code == 0);
  const auto traces = [&out] {
    int n = 0;
    for (const auto& e : fs::directory_iterator(out)) n += e.path().extension() == ".jsonl";
    return n;
  };
  CHECK(traces() == 4);
  write_file(dir / "g" / "notes.txt", "mine");  // not a trace: left alone
  REQUIRE(run_vbsim("gen crevice --rays 4 --set angles=20 -q -o " + out).exit_code == 0);
  CHECK(traces() == 1);
  CHECK(fs::exists(dir / "g" / "notes.txt"));
  const auto list = nlohmann::json::parse(read_file(dir / "g" / ".vbsim-gen.json"));
  CHECK(list["complete"] == true);
  CHECK(list["files"].size() == 2);  // one scene, one trace
  // score sees exactly the new case.
  const RunResult s = run_vbsim("score " + out + " -q --methods none --testers three-half-plane --out " +
                                (dir / "s.json").string());
  REQUIRE(s.exit_code == 0);
  CHECK(nlohmann::json::parse(read_file(dir / "s.json"))["families"][0]["traces"] == 1);
}

TEST_CASE("gen refuses a directory holding trace files it did not write", "[cli][gen]") {
  const auto dir = scratch_dir("gen_foreign");
  write_file(dir / "mine.jsonl", "{}\n");
  const SplitRun r = run_vbsim_split("gen coplanar --rays 4 -o " + dir.string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("mine.jsonl") && Catch::Contains("did not write"));
  CHECK(read_file(dir / "mine.jsonl") == "{}\n");  // untouched
  CHECK(!fs::exists(dir / "coplanar.jsonl"));
}
