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
  const std::string unit = (dir / "unit.json").string();
  // offset-errbound acts on the 808 rays with a parent surface: 128 operations,
  // ceil(128 / 4) + 5 = 37 cycles each, where the preset charges 4 per method.
  const nlohmann::json before = source_of("offset-errbound", "", dir);
  const nlohmann::json after = source_of("offset-errbound", unit, dir);
  CHECK(after["busy_cycles"].get<int64_t>() - before["busy_cycles"].get<int64_t>() == 808 * (37 - 4));
  CHECK(after["emission_unit"]["ops"] == 808 * 128);
  CHECK(after["emission_op_cycles"] == 0);
  // tmin acts on all 1,008 rays: 7 operations, ceil(7 / 4) + 5 = 7 cycles against 4.
  const nlohmann::json tmin_before = source_of("tmin", "", dir);
  const nlohmann::json tmin_after = source_of("tmin", unit, dir);
  CHECK(tmin_after["busy_cycles"].get<int64_t>() - tmin_before["busy_cycles"].get<int64_t>() == 1008 * (7 - 4));
  // primid and the validity bit have no emission-time arithmetic of the unit's
  // (the sign bit keeps sign_bit_cycles): the same lane cycles as without a unit.
  for (const char* m : {"primid", "validity-bit"}) {
    INFO(m);
    CHECK(source_of(m, unit, dir)["busy_cycles"] == source_of(m, "", dir)["busy_cycles"]);
  }
}
