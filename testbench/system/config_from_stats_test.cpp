// --config takes what a stats file records: its `config` block, or the whole
// stats file, reproducing the run that wrote it (functional and cycle mode).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

/// The parts of a stats file a rerun must reproduce (not the wall time, not the provenance).
nlohmann::json counted(nlohmann::json s) {
  s.erase("sim");
  s.erase("provenance");
  if (s.contains("hw")) {
    s["hw"].erase("rays_per_s");
    s["hw"].erase("wall_s");
  }
  return s;
}

}  // namespace

TEST_CASE("a stats file's config block, or the stats file itself, configures the same run", "[cli]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("config_from_stats");
  for (const std::string mode : {"functional", "cycle"}) {
    INFO(mode);
    const std::string base = "replay " + trace + " -q --mode " + mode;
    REQUIRE(run_vbsim(base + " -m validity-bit:vb-policy=vote:vb-guard-bits=3 --tester moller-trumbore --stats " +
                      (dir / "a.json").string() + (mode == "cycle" ? " --preset large" : ""))
                .exit_code == 0);
    const auto a = nlohmann::json::parse(read_file(dir / "a.json"));
    write_file(dir / "block.json", a["config"].dump(2));
    const RunResult b = run_vbsim(base + " --config " + (dir / "block.json").string() + " --stats " +
                                  (dir / "b.json").string());
    INFO(b.output);
    REQUIRE(b.exit_code == 0);
    const RunResult c = run_vbsim(base + " --config " + (dir / "a.json").string() + " --stats " +
                                  (dir / "c.json").string());
    REQUIRE(c.exit_code == 0);
    const auto bj = nlohmann::json::parse(read_file(dir / "b.json"));
    CHECK(bj["config"]["method"] == "validity-bit");
    CHECK(bj["config"]["validity_bit"]["policy"] == "vote");
    CHECK(bj["config"]["tester"] == "moller-trumbore");
    if (mode == "cycle") CHECK(bj["config"]["hw"]["preset"] == "large");
    CHECK(counted(bj) == counted(a));
    CHECK(counted(nlohmann::json::parse(read_file(dir / "c.json"))) == counted(a));
  }
}
