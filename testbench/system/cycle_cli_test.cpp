// vbsim replay --mode cycle from the command line: clean errors, the hw
// statistics, the VCD and the timeline.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <vector>

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

TEST_CASE("a trace scope that names no instance is a usage error naming it", "[system][cycle][tracing]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("cycle_scope");
  RunResult r = run_vbsim("replay " + trace + " --mode cycle -q --timeline " + (dir / "t.json").string() +
                          " --trace-scope accelerator.core_9");  // the small preset has cores 0 to 3
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("--trace-scope") && Catch::Contains("'accelerator.core_9'") &&
                           Catch::Contains("accelerator.core_3"));
  CHECK_FALSE(std::filesystem::exists(dir / "t.json"));
  r = run_vbsim("replay " + trace + " --mode cycle -q --timeline " + (dir / "t.json").string() +
                " --trace-scope 'accelerator.core_*'");
  CHECK(r.exit_code == 0);
  CHECK(std::filesystem::exists(dir / "t.json"));
}

TEST_CASE("interval statistics and a warm-up from the command line", "[system][cycle][stats]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("cycle_intervals");
  const RunResult r = run_vbsim("replay " + trace + " --mode cycle -q --interval-stats " + (dir / "iv.jsonl").string() +
                                " --interval 5000 --warmup-rays 100 --stats " + (dir / "s.json").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const auto s = nlohmann::json::parse(read_file(dir / "s.json"));
  CHECK(s["config"]["hw"]["sim"]["interval_cycles"] == 5000);
  CHECK(s["config"]["hw"]["sim"]["warmup_rays"] == 100);
  CHECK(s["hw"]["warmup"]["excluded_rays"].get<uint64_t>() >= 100);
  CHECK(s["hw"]["measured"]["rays"].get<uint64_t>() + s["hw"]["warmup"]["excluded_rays"].get<uint64_t>() == 1008);
  std::istringstream lines(read_file(dir / "iv.jsonl"));
  std::string line;
  uint64_t rays = 0, rows = 0;
  while (std::getline(lines, line)) {
    rays += nlohmann::json::parse(line)["rays"].get<uint64_t>();
    ++rows;
  }
  CHECK(rays == 1008);
  CHECK(rows == s["hw"]["cycles"].get<uint64_t>() / 5000 + 1);
  // Options that need a file or exclude each other.
  CHECK(run_vbsim("replay " + trace + " --mode cycle -q --interval 100").exit_code == 2);
  CHECK(run_vbsim("replay " + trace + " --mode cycle -q --warmup-rays 1 --warmup-cycles 1").exit_code == 2);
  CHECK(run_vbsim("replay " + trace + " --interval-stats " + (dir / "x.jsonl").string()).exit_code == 2);
}

TEST_CASE("the latency percentiles are those of the ray log's latencies sorted", "[system][cycle][stats]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("cycle_percentiles");
  const RunResult r = run_vbsim("replay " + trace + " --mode cycle -q --ray-log " + (dir / "rays.jsonl").string() +
                                " --stats " + (dir / "s.json").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  std::vector<uint64_t> latency;
  std::istringstream lines(read_file(dir / "rays.jsonl"));
  std::string line;
  while (std::getline(lines, line)) {
    const auto j = nlohmann::json::parse(line);
    latency.push_back(j["finish"].get<uint64_t>() - j["start"].get<uint64_t>());
  }
  REQUIRE(latency.size() == 1008);
  std::sort(latency.begin(), latency.end());
  // Nearest rank: the ceil(p/100 x 1008)-th smallest: p50 the 504th, p90 the 908th (907.2 up),
  // p95 the 958th (957.6 up), p99 the 998th (997.92 up).
  const auto stats = nlohmann::json::parse(read_file(dir / "s.json"));
  const auto& overall = stats["hw"]["latency_distribution"]["overall"];
  CHECK(overall["p50"] == latency[503]);
  CHECK(overall["p90"] == latency[907]);
  CHECK(overall["p95"] == latency[957]);
  CHECK(overall["p99"] == latency[997]);
  CHECK(overall["max"] == latency.back());
  CHECK(overall["min"] == latency.front());
}
