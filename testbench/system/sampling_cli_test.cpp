// vbsim replay --mode cycle --sample from the command line: the estimates and
// their intervals in the stats and the summary, the same hits file as a full
// run, the stopping rule, and the options' usage errors.
#include <catch2/catch.hpp>

#include <filesystem>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

/// The hits file without its provenance line.
std::string hits_body(const std::filesystem::path& p) {
  const std::string all = read_file(p);
  return all.substr(all.find('\n') + 1);
}

}  // namespace

TEST_CASE("a sampled replay writes its estimates with their intervals and the full run's hits",
          "[system][cycle][sampling]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("sampling_cli");
  const RunResult full = run_vbsim("replay " + trace + " --mode cycle -m validity-bit --stats " +
                                   (dir / "full.json").string() + " --hits " + (dir / "full.hits").string());
  REQUIRE(full.exit_code == 0);
  const RunResult r = run_vbsim("replay " + trace +
                                " --mode cycle -m validity-bit --sample --sample-unit 50 --sample-interval 4 "
                                "--sample-warmup 50 --sample-head 100 --sample-tail 100 --stats " +
                                (dir / "s.json").string() + " --hits " + (dir / "s.hits").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("sampled (ESTIMATES, 95% confidence intervals): cycles") &&
                           Catch::Contains("describe only the") && Catch::Contains("measuring ended: trace ended"));
  const auto s = nlohmann::json::parse(read_file(dir / "s.json"));
  const auto f = nlohmann::json::parse(read_file(dir / "full.json"));
  const auto& sampling = s["hw"]["sampling"];
  CHECK(sampling["parameters"]["unit"] == 50);
  CHECK(sampling["parameters"]["interval"] == 4);
  CHECK(sampling["parameters"]["warmup"] == 50);
  CHECK(sampling["parameters"]["total"] == 1008);
  CHECK(sampling["strata"]["head"]["rays"] == 100);
  CHECK(sampling["strata"]["tail"]["rays"] == 100);
  CHECK(sampling["confidence"] == 0.95);
  CHECK(sampling["units_measured"] == 4);  // body units 2, 6, 10, 14 from position 100
  const auto& iv = sampling["intervals"]["cycles"];
  REQUIRE(iv.is_array());
  CHECK(iv[0].get<double>() <= s["hw"]["cycles"].get<double>());
  CHECK(s["hw"]["cycles"].get<double>() <= iv[1].get<double>());
  CHECK(s["hw"]["rays"] == 1008);
  CHECK(s["verdicts"] == f["verdicts"]);
  CHECK(s["by_kind"] == f["by_kind"]);
  CHECK(hits_body(dir / "s.hits") == hits_body(dir / "full.hits"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("a sampled replay stops measuring at its error target and says so", "[system][cycle][sampling]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("sampling_stop");
  // A loose target reached after the minimum of units, and one never reached.
  RunResult r = run_vbsim("replay " + trace +
                          " --mode cycle --sample --sample-unit 20 --sample-interval 2 --sample-warmup 10 --sample-head 0 "
                          "--sample-tail 0 --sample-min-units 4 --sample-error 90% --stats " + (dir / "loose.json").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  auto s = nlohmann::json::parse(read_file(dir / "loose.json"));
  CHECK_THAT(s["hw"]["sampling"]["measuring_ended"].get<std::string>(), Catch::StartsWith("error target reached"));
  CHECK(s["hw"]["sampling"]["units_measured"].get<uint64_t>() < 25);
  CHECK(s["hw"]["sampling"]["parameters"]["error"] == Approx(0.9));
  r = run_vbsim("replay " + trace +
                " --mode cycle --sample --sample-unit 20 --sample-interval 2 --sample-warmup 10 --sample-head 0 "
                "--sample-tail 0 --sample-error 0.0001 --stats " + (dir / "tight.json").string());
  REQUIRE(r.exit_code == 0);
  s = nlohmann::json::parse(read_file(dir / "tight.json"));
  CHECK(s["hw"]["sampling"]["measuring_ended"] == "trace ended");
  // Units 1, 3, ..., 49 of 20 rays; the last is followed by fast-forwarded rays
  // only (positions 1000 .. 1007), so it ends in the drain and is left out.
  CHECK(s["hw"]["sampling"]["units_measured"] == 24);
  CHECK(s["hw"]["sampling"]["units_left_out"] == 1);
  std::filesystem::remove_all(dir);
}

TEST_CASE("sampling options are usage errors where they do not apply", "[system][cycle][sampling]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  struct Case {
    std::string args, message;
  };
  for (const Case& c : {Case{"--sample", "needs '--mode cycle'"},
                        Case{"--mode cycle --sample-unit 10", "need '--sample'"},
                        Case{"--mode cycle --sample --sample-unit 0", "option '--sample-unit': must be >= 1"},
                        Case{"--mode cycle --sample --sample-interval 4 --sample-offset 4",
                             "option '--sample-offset'"},
                        Case{"--mode cycle --sample --sample-confidence 1", "option '--sample-confidence'"},
                        Case{"--mode cycle --sample --sample-error abc", "option '--sample-error'"},
                        Case{"--mode cycle --sample --ray-log x.jsonl", "does not go with"}}) {
    INFO(c.args);
    const RunResult r = run_vbsim("replay " + trace + " -q " + c.args);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Catch::Contains(c.message));
  }
}
