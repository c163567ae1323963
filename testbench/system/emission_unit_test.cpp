// The ray source's emission unit (hw.source.emission_width, emission_depth):
// a ray's emission-time operations occupy its lane ceil(n / width) cycles in
// place of emission_op_cycles per method, and the unit's depth delays the ray
// without occupying the lane (pipelined); with shader cores (hw.shader.cores,
// the presets') the arithmetic runs there and the lane pays neither. Counted by
// hand on the bundled trace (1,008 rays, 808 of them with a parent surface).
#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

nlohmann::json source_of(const std::string& method, const std::string& config, const std::filesystem::path& dir) {
  const std::string stats = (dir / "s.json").string();
  const RunResult r = run_vbsim("replay -q " + source_dir() + "/traces/bunny/paths.jsonl --mode cycle -m " + method +
                                (config.empty() ? "" : " --config " + config) + " --stats " + stats);
  REQUIRE(r.exit_code == 0);
  return nlohmann::json::parse(read_file(stats))["hw"]["source"];
}

/// The first `n` lines of a ray log (--ray-log), parsed.
std::vector<nlohmann::json> first_rays(const std::string& log, size_t n) {
  std::istringstream lines(read_file(log));
  std::string line;
  std::vector<nlohmann::json> rays;
  while (rays.size() < n && std::getline(lines, line)) rays.push_back(nlohmann::json::parse(line));
  return rays;
}

}  // namespace

TEST_CASE("the emission unit's cycles follow each method's operation count", "[cli][hw][emission]") {
  const auto dir = scratch_dir("emission_unit");
  write_file(dir / "unit.json",
             R"({"hw": {"source": {"emission_width": 4, "emission_depth": 5}, "shader": {"cores": 0}}})");
  write_file(dir / "no_unit.json", R"({"hw": {"source": {"emission_width": 0}, "shader": {"cores": 0}}})");
  const std::string unit = (dir / "unit.json").string();
  const std::string no_unit = (dir / "no_unit.json").string();
  // offset-errbound acts on the 808 rays with a parent surface: 128 operations,
  // ceil(128 / 4) = 32 cycles of the lane each (the depth is not the lane's),
  // where no unit charges emission_op_cycles (4) per method.
  const nlohmann::json before = source_of("offset-errbound", no_unit, dir);
  const nlohmann::json after = source_of("offset-errbound", unit, dir);
  CHECK(after["busy_cycles"].get<int64_t>() - before["busy_cycles"].get<int64_t>() == 808 * (32 - 4));
  CHECK(after["emission_unit"]["ops"] == 808 * 128);
  CHECK(after["emission_op_cycles"] == 0);
  // tmin acts on all 1,008 rays: 7 operations, ceil(7 / 4) = 2 cycles against 4.
  const nlohmann::json tmin_before = source_of("tmin", no_unit, dir);
  const nlohmann::json tmin_after = source_of("tmin", unit, dir);
  CHECK(tmin_after["busy_cycles"].get<int64_t>() - tmin_before["busy_cycles"].get<int64_t>() == 1008 * (2 - 4));
  // primid and the validity bit have no emission-time arithmetic of the unit's
  // (the sign bit keeps sign_bit_cycles): the same lane cycles as without a unit.
  for (const char* m : {"primid", "validity-bit"}) {
    INFO(m);
    CHECK(source_of(m, unit, dir)["busy_cycles"] == source_of(m, no_unit, dir)["busy_cycles"]);
  }
  // The preset's own unit without its shader cores (small: 8 wide, 4 deep):
  // offset-errbound occupies a lane ceil(128 / 8) = 16 cycles per ray with a
  // parent surface, tmin ceil(7 / 8) = 1 per ray.
  write_file(dir / "preset_unit.json", R"({"hw": {"shader": {"cores": 0}}})");
  const std::string preset_unit = (dir / "preset_unit.json").string();
  CHECK(source_of("offset-errbound", preset_unit, dir)["busy_cycles"].get<int64_t>() -
            before["busy_cycles"].get<int64_t>() ==
        808 * (16 - 4));
  CHECK(source_of("tmin", preset_unit, dir)["busy_cycles"].get<int64_t>() - tmin_before["busy_cycles"].get<int64_t>() ==
        1008 * (1 - 4));
  // The preset as shipped, with its shader cores: the arithmetic is theirs, the
  // lanes pay what primid's pay (issue interval and sign bits), and the cores
  // report every operation.
  const nlohmann::json errbound_cores = source_of("offset-errbound", "", dir);
  CHECK(errbound_cores["busy_cycles"] == source_of("primid", "", dir)["busy_cycles"]);
  CHECK(errbound_cores["busy_cycles"].get<int64_t>() == before["busy_cycles"].get<int64_t>() - 808 * 4);
}

TEST_CASE("the emission unit's depth delays a ray, not its lane", "[cli][hw][emission]") {
  // Every ray independent (--deps off), one lane, a unit 4 wide and 5 deep, no
  // shader cores: tmin's 7 operations occupy the lane 1 (issue interval) +
  // ceil(7 / 4) = 3 cycles per ray, and each ray reaches the dispatcher 5
  // cycles after its lane is free. Ray 0 starts emitting at cycle 0 and is
  // dispatched at 3 + 5 = 8; ray 1 starts at 3 (not 8, as when the depth held
  // the lane) and is dispatched at 11; ray 2 starts at 6.
  const auto dir = scratch_dir("emission_depth");
  write_file(dir / "unit.json",
             R"({"hw": {"source": {"emission_width": 4, "emission_depth": 5}, "shader": {"cores": 0}}})");
  const std::string log = (dir / "rays.jsonl").string();
  const RunResult r = run_vbsim("replay -q " + source_dir() + "/traces/bunny/paths.jsonl --mode cycle --deps off -m tmin"
                                " --config " + (dir / "unit.json").string() + " --ray-log " + log);
  REQUIRE(r.exit_code == 0);
  const std::vector<nlohmann::json> rays = first_rays(log, 3);
  REQUIRE(rays.size() == 3);
  CHECK(rays[0]["emit"] == 0);
  CHECK(rays[0]["start"] == 8);
  CHECK(rays[1]["emit"] == 3);
  CHECK(rays[1]["start"] == 11);
  CHECK(rays[2]["emit"] == 6);
  CHECK(rays[2]["start"] == 14);
}

TEST_CASE("with shader cores a ray reaches its lane after its arithmetic there", "[cli][hw][emission]") {
  // One shader core of 2 lanes, 1 operation a lane a cycle, 4 cycles of
  // pipeline; one lane of the source, no emission unit in the way. tmin's 7
  // operations: ray 0, ready at 0, is done at 7 + 4 = 11 and emitted then (its
  // lane pays its issue interval, 1 cycle: dispatched at 12); ray 1 takes the
  // core's issue slots from cycle ceil(7 / 2) = 4: done at 15, dispatched at 16.
  const auto dir = scratch_dir("shader_cores");
  write_file(dir / "cores.json", R"({"hw": {"shader": {"cores": 1, "simd_lanes": 2, "ops_per_lane_cycle": 1,
                                                         "pipeline_latency": 4}}})");
  const std::string log = (dir / "rays.jsonl").string(), stats = (dir / "s.json").string();
  const RunResult r = run_vbsim("replay -q " + source_dir() + "/traces/bunny/paths.jsonl --mode cycle --deps off -m tmin"
                                " --config " + (dir / "cores.json").string() + " --ray-log " + log + " --stats " + stats);
  REQUIRE(r.exit_code == 0);
  const std::vector<nlohmann::json> rays = first_rays(log, 2);
  REQUIRE(rays.size() == 2);
  CHECK(rays[0]["ready"] == 0);
  CHECK(rays[0]["emit"] == 11);
  CHECK(rays[0]["start"] == 12);
  CHECK(rays[1]["emit"] == 15);
  CHECK(rays[1]["start"] == 16);
  const nlohmann::json cores = nlohmann::json::parse(read_file(stats))["hw"]["emission"]["shader_cores"];
  CHECK(cores["rays"] == 1008);
  CHECK(cores["ops"] == 1008 * 7);
}
