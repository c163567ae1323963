// Energy and area through the vbsim program: the technology file's errors, the
// area table and its linearity in the file's figures, and the operations'
// energy equal in both replay modes (docs/energy.md).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

std::string shipped_tech() { return source_dir() + "/model/energy/tech/45nm.json"; }

/// The shipped file with every area figure (operators, register and SRAM bits) times `k`.
nlohmann::json scaled_areas(double k) {
  nlohmann::json t = nlohmann::json::parse(read_file(shipped_tech()));
  for (auto& f : t["area_mm2"]) f["value"] = f["value"].get<double>() * k;
  return t;
}

}  // namespace

TEST_CASE("a bad technology file is an error naming the file and the field", "[cli][energy]") {
  const auto dir = scratch_dir("tech_errors");
  nlohmann::json t = nlohmann::json::parse(read_file(shipped_tech()));
  t["energy_pj"]["fp32_mul"]["value"] = -3.7;
  write_file(dir / "bad.json", t.dump());
  const std::string bad = (dir / "bad.json").string();
  for (const std::string& cmd : {"replay " + source_dir() + "/traces/bunny/paths.jsonl -q --tech " + bad,
                                 "hw --area --tech " + bad}) {
    INFO(cmd);
    const RunResult r = run_vbsim(cmd);
    CHECK(r.exit_code != 0);
    CHECK(r.exit_code < 128);
    CHECK_THAT(r.output, Catch::Contains(bad + ": field 'energy_pj.fp32_mul.value': must be >= 0"));
  }
}

TEST_CASE("vbsim hw --area: every instance, the avoidance units apart, linear in the file's areas",
          "[cli][energy]") {
  const auto dir = scratch_dir("hw_area");
  const RunResult vb = run_vbsim("hw --area -m validity-bit");
  REQUIRE(vb.exit_code == 0);
  // The small preset: 4 cores, one avoidance unit each.
  CHECK_THAT(vb.output, Catch::Contains("avoidance_unit") && Catch::Contains("chip "));
  const RunResult eb = run_vbsim("hw --area -m offset-errbound --json " + (dir / "eb.json").string());
  REQUIRE(eb.exit_code == 0);
  const nlohmann::json a1 = nlohmann::json::parse(read_file(dir / "eb.json"))["area"];
  CHECK(a1["instances"]["avoidance_unit"] == 0);
  CHECK(a1["avoidance_units_mm2"] == 0.0);
  CHECK(a1["instances"]["emission_lane"] == 1);
  write_file(dir / "double.json", scaled_areas(2).dump());
  REQUIRE(run_vbsim("hw --area -m offset-errbound --tech " + (dir / "double.json").string() + " --json " +
                    (dir / "eb2.json").string())
              .exit_code == 0);
  const nlohmann::json a2 = nlohmann::json::parse(read_file(dir / "eb2.json"))["area"];
  CHECK(a2["chip_mm2"].get<double>() == Approx(2 * a1["chip_mm2"].get<double>()));
  CHECK(a2["per_instance_mm2"]["emission_lane"].get<double>() ==
        Approx(2 * a1["per_instance_mm2"]["emission_lane"].get<double>()));
}

TEST_CASE("the operations' energy is the same in both replay modes, hw.energy adds memory and leakage",
          "[cli][energy]") {
  const auto dir = scratch_dir("energy_modes");
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto f = (dir / "f.json").string(), c = (dir / "c.json").string();
  REQUIRE(run_vbsim("replay -q " + trace + " -m validity-bit --stats " + f).exit_code == 0);
  REQUIRE(run_vbsim("replay -q " + trace + " -m validity-bit --mode cycle --stats " + c).exit_code == 0);
  const nlohmann::json fj = nlohmann::json::parse(read_file(f)), cj = nlohmann::json::parse(read_file(c));
  // The same searches (a test checks the hits): the same counts, the same operations' energy.
  CHECK(fj["traversal"] == cj["traversal"]);
  CHECK(fj["energy"]["dynamic_total_pj"].get<double>() == Approx(cj["energy"]["dynamic_total_pj"].get<double>()));
  const nlohmann::json& e = cj["hw"]["energy"];
  double parts = 0, ops = 0;
  for (const auto& [part, pj] : e["dynamic_pj"].items()) {
    parts += pj.get<double>();
    if (fj["energy"]["dynamic_pj"].contains(part)) ops += pj.get<double>();
  }
  CHECK(ops == Approx(fj["energy"]["dynamic_total_pj"].get<double>()));
  CHECK(parts == Approx(e["dynamic_total_pj"].get<double>()));
  CHECK(e["dynamic_pj"]["dram"].get<double>() > 0);  // the cold caches read the BVH from DRAM
  CHECK(e["total_pj"].get<double>() == Approx(e["dynamic_total_pj"].get<double>() + e["static_pj"].get<double>()));
  CHECK(e["per_ray_pj"].get<double>() * cj["rays"].get<double>() == Approx(e["total_pj"].get<double>()));
  CHECK(e["mrays_per_j"].get<double>() == Approx(cj["rays"].get<double>() / (e["total_pj"].get<double>() * 1e-6)));
  // Functional mode prints the operations' energy.
  const RunResult r = run_vbsim("replay " + trace + " -m validity-bit");
  CHECK_THAT(r.output, Catch::Contains("energy (operations only, no memory):"));
}

TEST_CASE("the 7 nm technology file prices every preset, smaller and cheaper than 45 nm", "[cli][energy]") {
  const auto dir = scratch_dir("tech_7nm");
  const std::string tech7 = source_dir() + "/model/energy/tech/7nm.json";
  for (const std::string preset : {"small", "large", "rtcore"}) {
    INFO(preset);
    const std::string a7 = (dir / ("a7-" + preset + ".json")).string(), a45 = (dir / ("a45-" + preset + ".json")).string();
    const RunResult r = run_vbsim("hw --area -m validity-bit --preset " + preset + " --tech " + tech7 + " --json " + a7);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.output, Catch::Contains("7nm.json") && Catch::Contains("chip "));
    REQUIRE(run_vbsim("hw --area -m validity-bit --preset " + preset + " --json " + a45).exit_code == 0);
    const double chip7 = nlohmann::json::parse(read_file(a7))["area"]["chip_mm2"].get<double>();
    const double chip45 = nlohmann::json::parse(read_file(a45))["area"]["chip_mm2"].get<double>();
    CHECK(chip7 > 0);
    CHECK(chip7 < chip45 / 5);
    // A cycle-level replay on the preset, priced at 7 nm: the same chip.
    const std::string s = (dir / ("s7-" + preset + ".json")).string();
    REQUIRE(run_vbsim("replay -q " + source_dir() + "/traces/bunny/paths.jsonl -m validity-bit --mode cycle --preset " +
                      preset + " --tech " + tech7 + " --stats " + s)
                .exit_code == 0);
    const nlohmann::json hw = nlohmann::json::parse(read_file(s))["hw"];
    CHECK(hw["energy"]["per_ray_pj"].get<double>() > 0);
    CHECK(hw["area"]["chip_mm2"].get<double>() == chip7);
  }
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const std::string s7 = (dir / "s7.json").string(), s45 = (dir / "s45.json").string();
  REQUIRE(run_vbsim("replay -q " + trace + " -m validity-bit --mode cycle --tech " + tech7 + " --stats " + s7).exit_code == 0);
  REQUIRE(run_vbsim("replay -q " + trace + " -m validity-bit --mode cycle --stats " + s45).exit_code == 0);
  const nlohmann::json e7 = nlohmann::json::parse(read_file(s7))["hw"]["energy"];
  const nlohmann::json e45 = nlohmann::json::parse(read_file(s45))["hw"]["energy"];
  CHECK(e7["tech"] == tech7);
  CHECK(e7["per_ray_pj"].get<double>() > 0);
  CHECK(e7["per_ray_pj"].get<double>() < e45["per_ray_pj"].get<double>());
  // The same DRAM figure (DRAM energy is the DRAM's, not the node's).
  CHECK(e7["dynamic_pj"]["dram"].get<double>() == Approx(e45["dynamic_pj"]["dram"].get<double>()));
}

TEST_CASE("a memory array outside the technology file's SRAM table is said in the text summary", "[cli][energy]") {
  const auto dir = scratch_dir("sram_range");
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  // The small preset's 16 KB L1 and 1 MB L2 lie inside the shipped table (8 KB to 1 MB): no warning.
  const RunResult inside = run_vbsim("hw --area");
  REQUIRE(inside.exit_code == 0);
  CHECK_THAT(inside.output, !Catch::Contains("warning:"));
  // A 4 KB L1 lies below it, a 2 MB L2 above.
  write_file(dir / "c.json", R"({"hw": {"memory": {"l1": {"size_bytes": 4096}, "l2": {"size_bytes": 2097152}}}})");
  const std::string config = (dir / "c.json").string();
  const std::string tech = source_dir() + "/model/energy/tech/45nm.json";
  const std::string l1 = "warning: the L1 (4 KB) is below the SRAM table of " + tech + " (8 KB to 1 MB)";
  const std::string l2 = "warning: the L2 (2 MB) is above the SRAM table of " + tech + " (8 KB to 1 MB)";
  const RunResult area = run_vbsim("hw --area --config " + config + " --tech " + tech);
  REQUIRE(area.exit_code == 0);
  CHECK_THAT(area.output, Catch::Contains(l1) && Catch::Contains(l2));
  const std::string stats = (dir / "s.json").string();
  const RunResult replay =
      run_vbsim("replay " + trace + " -m validity-bit --mode cycle --config " + config + " --tech " + tech + " --stats " + stats);
  REQUIRE(replay.exit_code == 0);
  CHECK_THAT(replay.output, Catch::Contains(l1 + ": its access energy is extrapolated") && Catch::Contains(l2));
  CHECK(nlohmann::json::parse(read_file(stats))["hw"]["energy"]["sram_size_extrapolated"] == true);
}
