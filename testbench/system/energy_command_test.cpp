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
