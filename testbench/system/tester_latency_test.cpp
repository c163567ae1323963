// Each tester's latency derived from its own arithmetic drives the cycle-level
// model (hw.triangle.derive, docs/hw-model.md "Tester latency from its
// arithmetic"): with one core, one slot, ideal memory and independent rays every
// leaf waits for its last triangle result, so a run's cycles move by exactly
// (latency - 20) x leaf reads against the same run at a fixed 20-cycle tester,
// and the answers stay the same byte for byte.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

struct Run {
  int64_t cycles = 0, leaf_fetches = 0, latency = 0;
  std::string hits;
};

Run replay(const std::string& tester, const std::string& config, const std::filesystem::path& dir) {
  const std::string stats = (dir / "s.json").string(), hits = (dir / "h.jsonl").string();
  const RunResult r = run_vbsim("replay -q " + source_dir() + "/traces/bunny/paths.jsonl --mode cycle --deps off " +
                                "-m validity-bit --tester " + tester + " --config " + config + " --stats " + stats +
                                " --hits " + hits);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(read_file(stats));
  return {j["hw"]["cycles"].get<int64_t>(), j["hw"]["memory"]["leaf_fetches"].get<int64_t>(),
          j["config"]["hw"]["triangle"]["latency"].get<int64_t>(),
          read_file(hits).substr(read_file(hits).find('\n'))};  // the lines after the header (its command differs)
}

}  // namespace

TEST_CASE("each tester's derived latency sets its cycles and leaves the hits alone", "[cli][hw][tester-timing]") {
  const auto dir = scratch_dir("tester_latency");
  const std::string base = R"("cores": 1, "slots_per_core": 1, "memory": {"ideal": true})";
  write_file(dir / "fixed.json", R"({"hw": {)" + base + R"(, "triangle": {"latency": 20}}})");
  write_file(dir / "derived.json", R"({"hw": {)" + base + R"(, "triangle": {"derive": true}}})");
  // The chains counted by hand (tester_timing_test.cpp): 33, 33 and 38 cycles.
  const std::pair<const char*, int64_t> testers[] = {
      {"three-half-plane", 33}, {"moller-trumbore", 33}, {"pbrt-watertight", 38}};
  int64_t derived_cycles[3] = {};
  int i = 0;
  for (const auto& [tester, latency] : testers) {
    INFO(tester);
    const Run fixed = replay(tester, (dir / "fixed.json").string(), dir);
    const Run derived = replay(tester, (dir / "derived.json").string(), dir);
    CHECK(fixed.latency == 20);
    CHECK(derived.latency == latency);
    CHECK(derived.leaf_fetches == fixed.leaf_fetches);
    CHECK(derived.cycles - fixed.cycles == (latency - 20) * fixed.leaf_fetches);
    CHECK(derived.hits == fixed.hits);
    derived_cycles[i++] = derived.cycles;
  }
  // The two 33-cycle testers against pbrt's 38: pbrt's run is the slowest.
  CHECK(derived_cycles[2] > derived_cycles[0]);
  CHECK(derived_cycles[2] > derived_cycles[1]);
}
