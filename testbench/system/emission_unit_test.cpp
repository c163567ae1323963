// The ray source's emission unit (hw.source.emission_width, emission_depth):
// a ray's emission-time operations hold its lane ceil(n / width) + depth
// cycles in place of emission_op_cycles per method, counted by hand on the
// bundled trace (1,008 rays, 808 of them with a parent surface).
#include <catch2/catch.hpp>

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

}  // namespace

TEST_CASE("the emission unit's cycles follow each method's operation count", "[cli][hw][emission]") {
  const auto dir = scratch_dir("emission_unit");
  write_file(dir / "unit.json", R"({"hw": {"source": {"emission_width": 4, "emission_depth": 5}}})");
  write_file(dir / "no_unit.json", R"({"hw": {"source": {"emission_width": 0}}})");
  const std::string unit = (dir / "unit.json").string();
  const std::string no_unit = (dir / "no_unit.json").string();
  // offset-errbound acts on the 808 rays with a parent surface: 128 operations,
  // ceil(128 / 4) + 5 = 37 cycles each, where no unit charges emission_op_cycles
  // (4) per method.
  const nlohmann::json before = source_of("offset-errbound", no_unit, dir);
  const nlohmann::json after = source_of("offset-errbound", unit, dir);
  CHECK(after["busy_cycles"].get<int64_t>() - before["busy_cycles"].get<int64_t>() == 808 * (37 - 4));
  CHECK(after["emission_unit"]["ops"] == 808 * 128);
  CHECK(after["emission_op_cycles"] == 0);
  // tmin acts on all 1,008 rays: 7 operations, ceil(7 / 4) + 5 = 7 cycles against 4.
  const nlohmann::json tmin_before = source_of("tmin", no_unit, dir);
  const nlohmann::json tmin_after = source_of("tmin", unit, dir);
  CHECK(tmin_after["busy_cycles"].get<int64_t>() - tmin_before["busy_cycles"].get<int64_t>() == 1008 * (7 - 4));
  // primid and the validity bit have no emission-time arithmetic of the unit's
  // (the sign bit keeps sign_bit_cycles): the same lane cycles as without a unit.
  for (const char* m : {"primid", "validity-bit"}) {
    INFO(m);
    CHECK(source_of(m, unit, dir)["busy_cycles"] == source_of(m, no_unit, dir)["busy_cycles"]);
  }
  // The preset's own unit (small: 8 wide, 4 deep): offset-errbound holds a lane
  // ceil(128 / 8) + 4 = 20 cycles per ray with a parent surface, tmin ceil(7 / 8)
  // + 4 = 5 per ray.
  CHECK(source_of("offset-errbound", "", dir)["busy_cycles"].get<int64_t>() - before["busy_cycles"].get<int64_t>() ==
        808 * (20 - 4));
  CHECK(source_of("tmin", "", dir)["busy_cycles"].get<int64_t>() - tmin_before["busy_cycles"].get<int64_t>() ==
        1008 * (5 - 4));
}
