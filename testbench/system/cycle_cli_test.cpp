// vbsim replay --mode cycle from the command line: clean errors, the hw
// statistics, the VCD and the timeline.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

TEST_CASE("cycle mode reports an impossible cache and a bad hw field cleanly", "[system][cycle]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("cycle_errors");
  write_file(dir / "real.json", R"({"hw": {"memory": {"ideal": false, "l1": {"ways": 512}}}})");
  RunResult r = run_vbsim("replay " + trace + " --mode cycle --config " + (dir / "real.json").string());
  CHECK(r.exit_code == 1);  // a bad input file: a runtime error
  CHECK_THAT(r.output, Catch::Contains("real.json: field 'hw.memory.l1.size_bytes'"));
  write_file(dir / "bad.json", R"({"hw": {"box": {"count": -1}}})");
  r = run_vbsim("replay " + trace + " --mode cycle --config " + (dir / "bad.json").string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("field 'hw.box.count'"));
  r = run_vbsim("replay " + trace + " --mode cycle --preset medium");
  CHECK(r.exit_code == 2);  // a bad command line: a usage error
  CHECK_THAT(r.output, Catch::Contains("unknown preset 'medium'"));
}

TEST_CASE("cycle mode writes the hw statistics, a VCD and a timeline", "[system][cycle]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("cycle_stats");
  write_file(dir / "ideal.json", R"({"method": "validity-bit", "hw": {"memory": {"ideal": true}}})");
  const RunResult r = run_vbsim("replay " + trace + " --mode cycle --preset small --config " +
                                (dir / "ideal.json").string() + " --stats " + (dir / "s.json").string() + " --vcd " +
                                (dir / "w.vcd").string() + " --timeline " + (dir / "t.json").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("rays/cycle") && Catch::Contains("utilisation"));
  const auto s = nlohmann::json::parse(read_file(dir / "s.json"));
  CHECK(s["sim"]["mode"] == "cycle");
  CHECK(s["config"]["hw"]["preset"] == "small");
  const auto& hw = s["hw"];
  CHECK(hw["rays"] == 1008);
  CHECK(hw["cycles"].get<uint64_t>() > 0);
  CHECK(hw["rays_per_s"].get<double>() == Approx(hw["rays_per_cycle"].get<double>() * 400e6));
  CHECK(hw["memory"]["port"]["model"] == "ideal");
  CHECK(hw["avoidance"]["by_kind"]["shadow"]["rejection_rate"].get<double>() >= 0);
  uint64_t histogram = 0;
  for (const auto& n : hw["latency"]["histogram"]) histogram += n.get<uint64_t>();
  CHECK(histogram == 1008);
  CHECK_THAT(read_file(dir / "w.vcd"), Catch::Contains("$var") && Catch::Contains("rays_done"));
  const auto tl = nlohmann::json::parse(read_file(dir / "t.json"));
  CHECK(tl["traceEvents"].size() > 0);
}
