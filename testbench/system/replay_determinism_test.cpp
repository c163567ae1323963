// Determinism: the same inputs give byte-identical statistics (less the
// wall-clock fields) and hits files, run after run, in both modes, and
// `vbsim score` gives the same table whatever its thread count.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

/// The JSON text of `path` without the fields that measure wall-clock time
/// (and, when `provenance` is false, without the provenance, which names the
/// command line).
std::string without_clock(const std::filesystem::path& path, bool provenance = true) {
  nlohmann::json j = nlohmann::json::parse(read_file(path));
  if (!provenance) j.erase("provenance");
  const std::function<void(nlohmann::json&)> strip = [&](nlohmann::json& v) {
    if (v.is_object()) {
      for (const char* key : {"wall_s", "rays_per_s", "sim_wall_s", "sc_wall_s"}) v.erase(key);
      for (auto& [key, value] : v.items()) strip(value);
    } else if (v.is_array()) {
      for (auto& e : v) strip(e);
    }
  };
  strip(j);
  return j.dump(1);
}

}  // namespace

TEST_CASE("replays give byte-identical stats and hits across runs", "[system][determinism]") {
  const auto dir = scratch_dir("determinism");
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  for (const char* mode : {"functional", "cycle"}) {
    INFO(mode);
    std::string stats[2], hits[2];
    // The same command line both times: the files' provenance names it.
    const auto s = dir / "s.json", h = dir / "h.jsonl";
    for (int run = 0; run < 2; ++run) {
      const RunResult r = run_vbsim("replay " + trace + " -q --method validity-bit --hitpoint barycentric --mode " +
                                    mode + " --stats " + s.string() + " --hits " + h.string());
      REQUIRE(r.exit_code == 0);
      stats[run] = without_clock(s);
      hits[run] = read_file(h);
      std::filesystem::remove(s);
      std::filesystem::remove(h);
    }
    CHECK(stats[0] == stats[1]);
    CHECK(hits[0] == hits[1]);
    CHECK(hits[0].size() > 1008 * 30);
    CHECK(stats[0].find("\"provenance\"") != std::string::npos);
  }
}

TEST_CASE("score gives the same table with one thread and with three", "[system][determinism][score]") {
  const auto dir = scratch_dir("score_threads");
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  std::string table[2];
  const int threads[2] = {1, 3};
  for (int k = 0; k < 2; ++k) {
    const auto out = dir / ("score" + std::to_string(k) + ".json");
    const RunResult r = run_vbsim("score " + trace + " -q --methods validity-bit,tmin,offset-normal,primid --threads " +
                                  std::to_string(threads[k]) + " --out " + out.string());
    REQUIRE(r.exit_code == 0);
    table[k] = without_clock(out, false);  // the command lines differ in --threads
  }
  CHECK(table[0] == table[1]);
}
