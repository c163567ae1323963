// Units shared by groups of cores (hw.<unit>.share, docs/config.md) through the
// vbsim program: the same hits, the same operations, a quarter of the
// avoidance units priced, and their utilisation over the units that exist.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

TEST_CASE("one avoidance unit shared by four cores: same hits and operations, one unit priced", "[cli][share]") {
  const auto dir = scratch_dir("unit_sharing");
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  nlohmann::json stats[2];
  std::string hits[2];
  for (int shared = 0; shared < 2; ++shared) {
    const auto cfg = dir / ("share" + std::to_string(shared) + ".json");
    write_file(cfg, shared ? R"({"hw": {"avoidance": {"share": 4}}})" : R"({"hw": {}})");
    const auto s = dir / ("s" + std::to_string(shared) + ".json");
    const auto h = dir / ("h" + std::to_string(shared) + ".jsonl");
    const RunResult r = run_vbsim("replay " + trace + " --mode cycle -m validity-bit -q --config " + cfg.string() +
                                  " --stats " + s.string() + " --hits " + h.string());
    REQUIRE(r.exit_code == 0);
    stats[shared] = nlohmann::json::parse(read_file(s));
    const std::string all = read_file(h);
    hits[shared] = all.substr(all.find('\n') + 1);  // after the provenance line
  }
  CHECK(hits[0] == hits[1]);
  const nlohmann::json &own = stats[0]["hw"], &one = stats[1]["hw"];
  REQUIRE(own["units"]["avoidance"]["ops"].get<uint64_t>() > 0);
  CHECK(own["units"]["avoidance"]["ops"] == one["units"]["avoidance"]["ops"]);
  CHECK(own["area"]["instances"]["avoidance_unit"] == 4);
  CHECK(one["area"]["instances"]["avoidance_unit"] == 1);
  const double unit = own["area"]["per_instance_mm2"]["avoidance_unit"].get<double>();
  CHECK(one["area"]["per_instance_mm2"]["avoidance_unit"].get<double>() == Approx(unit));
  CHECK(own["area"]["chip_mm2"].get<double>() - one["area"]["chip_mm2"].get<double>() == Approx(3 * unit));
  // The same operations over a quarter of the pipelines: four times the busy fraction, cycles aside.
  const double u_own = own["units"]["avoidance"]["utilisation"].get<double>() * own["cycles"].get<double>();
  const double u_one = one["units"]["avoidance"]["utilisation"].get<double>() * one["cycles"].get<double>();
  CHECK(u_one == Approx(4 * u_own));
  CHECK(one["cycles"].get<uint64_t>() >= own["cycles"].get<uint64_t>());
}
