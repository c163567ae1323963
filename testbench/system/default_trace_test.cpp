// The bundled default trace end to end: the main job, committed statistics per
// method, lossless text/binary conversion, and the oracle reproducing `expect`.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <sstream>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {
std::string default_trace() { return source_dir() + "/traces/bunny/paths.jsonl"; }

std::string quote_args(const nlohmann::json& args) {
  std::string s;
  for (const auto& a : args) s += " " + a.get<std::string>();
  return s;
}
}  // namespace

TEST_CASE("vbsim with no arguments replays the default trace with the validity bit", "[system]") {
  const RunResult r = run_vbsim("");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("method validity-bit") && Catch::Contains("rays") &&
                           Catch::Contains("rejected") && Catch::Contains("rays/s"));
  // The trade-off table: 95% Wilson intervals on every per-million figure (369
  // self hits of 808 secondary rays without a method; a 0 of 808 has the upper
  // bound z^2 / (808 + z^2); 0 of 200 camera misses likewise) and energy per ray.
  CHECK_THAT(r.output, Catch::Contains("secondary err/M [95%]") && Catch::Contains("camera /M [95%]") &&
                           Catch::Contains("pJ/ray") && Catch::Contains("456683 [422623, 491153]") &&
                           Catch::Contains("0 [0, 4732]") && Catch::Contains("0 [0, 18845]"));
}

TEST_CASE("default trace statistics match the committed expectations", "[system]") {
  const auto expected =
      nlohmann::json::parse(read_file(source_dir() + "/traces/bunny/paths.expected.json"));
  const auto dir = scratch_dir("expected_stats");
  for (const auto& [label, want] : expected["runs"].items()) {
    const auto stats_path = (dir / "stats.json").string();
    const RunResult r =
        run_vbsim("replay " + default_trace() + " --quiet --stats " + stats_path + quote_args(want["args"]));
    INFO(label << ": " << r.output);
    REQUIRE(r.exit_code == 0);
    const auto got = nlohmann::json::parse(read_file(stats_path));
    CHECK(got["rays"] == want["rays"]);
    CHECK(got["verdicts"] == want["verdicts"]);
    for (const auto& [kind, verdicts] : want["by_kind"].items())
      CHECK(got["by_kind"][kind]["verdicts"] == verdicts);
    for (const auto& [key, value] : want["avoidance"].items()) CHECK(got["avoidance"][key] == value);
    CHECK(got["emission_fallbacks"] == want["emission_fallbacks"]);
    // The effective configuration is echoed, and the counts add up.
    CHECK(got["config"]["trace"] == default_trace());
    uint64_t sum = 0;
    for (const auto& [v, n] : got["verdicts"].items()) sum += n.get<uint64_t>();
    CHECK(sum == got["rays"].get<uint64_t>());
  }
}

TEST_CASE("the hits file has one line per ray with its verdict", "[system]") {
  const auto dir = scratch_dir("hits");
  const RunResult r = run_vbsim("replay " + default_trace() + " -q -m validity-bit --hits " + (dir / "h.jsonl").string());
  REQUIRE(r.exit_code == 0);
  std::istringstream lines(read_file(dir / "h.jsonl"));
  std::string line;
  REQUIRE(std::getline(lines, line));  // the header: what wrote the file
  const auto header = nlohmann::json::parse(line);
  CHECK(header["format"] == "vbsim-hits");
  CHECK(header["provenance"]["inputs"][0]["path"] == default_trace());
  int64_t n = 0, rejected = 0;
  while (std::getline(lines, line)) {
    const auto j = nlohmann::json::parse(line);
    CHECK(j["id"] == n);  // the bundled trace numbers its rays 0, 1, 2, ...
    CHECK(j.contains("verdict"));
    if (j["prim"] != -1) CHECK((j.contains("t") && j.contains("u") && j.contains("v") && j.contains("front")));
    rejected += j["rejected"].get<int64_t>();
    ++n;
  }
  CHECK(n == 1008);
  CHECK(rejected > 0);  // the unit rejected re-hits of parent surfaces
}

TEST_CASE("the default trace converts text -> binary -> text without loss", "[system]") {
  const auto dir = scratch_dir("convert");
  const auto vbt = (dir / "paths.vbt").string(), back = (dir / "paths.jsonl").string();
  REQUIRE(run_vbsim("convert " + default_trace() + " -o " + vbt).exit_code == 0);
  REQUIRE(run_vbsim("convert " + vbt + " -o " + back).exit_code == 0);
  // Only the header's relative scene path may differ (the copy lives elsewhere).
  auto body = [](const std::string& text) { return text.substr(text.find('\n')); };
  CHECK(body(read_file(back)) == body(read_file(default_trace())));
  // And the binary trace replays to the same statistics.
  const RunResult a = run_vbsim("replay " + default_trace() + " -m validity-bit");
  const RunResult b = run_vbsim("replay " + vbt + " -m validity-bit");
  CHECK(a.output.substr(a.output.find("verdicts"), 200) == b.output.substr(b.output.find("verdicts"), 200));
}

TEST_CASE("the oracle reproduces the committed expectations of the default trace", "[system][oracle]") {
  const auto dir = scratch_dir("oracle");
  const auto out = (dir / "again.jsonl").string();
  const RunResult r = run_vbsim("oracle " + default_trace() + " -o " + out);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  auto body = [](const std::string& text) { return text.substr(text.find('\n')); };
  CHECK(body(read_file(out)) == body(read_file(default_trace())));
}
