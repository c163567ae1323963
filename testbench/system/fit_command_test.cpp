// vbsim fit end to end on hand-built traces with known answers: two parallel
// planes P (z = 0, triangle 0) and Q (z = 1, triangle 1), rays along +z.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;
using nlohmann::json;

namespace {

const char* kTwoPlanes =
    "v -10 -10 0\nv 10 -10 0\nv 0 10 0\nv -10 -10 1\nv 10 -10 1\nv 0 10 1\nf 1 2 3\nf 4 5 6\n";

/// A trace over the two planes with `rays` (JSON lines), expectations filled in by the oracle.
std::string two_plane_trace(const std::filesystem::path& dir, const std::string& rays) {
  write_file(dir / "planes.obj", kTwoPlanes);
  write_file(dir / "raw.jsonl", "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"planes.obj\"}\n" + rays);
  const auto trace = (dir / "planes.jsonl").string();
  const RunResult r = run_vbsim("oracle " + (dir / "raw.jsonl").string() + " -o " + trace);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return trace;
}

// Ray 0 hits P at the origin; ray 1, its child, starts 0.001 below P going up:
// it re-hits P at t = 0.001 (a self hit) and should hit Q at t = 1.001. So tmin
// must lie between 0.001 and 1.001.
const char* kChildBelowParent =
    "{\"id\":0,\"o\":[0,0,-5],\"d\":[0,0,1]}\n"
    "{\"id\":1,\"parent\":0,\"kind\":\"refract\",\"o\":[0,0,-0.001],\"d\":[0,0,1],\"parent_prim\":0}\n";

json fit_json(const std::string& args, const std::filesystem::path& dir) {
  const auto out = (dir / "fit.json").string();
  const RunResult r = run_vbsim("fit " + args + " --json " + out);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return json::parse(read_file(out));
}

/// "OPTION VALUE" with the value printed to round-trip a double.
std::string fmt_double_option(const std::string& option, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return option + " " + buf;
}

std::string verdicts_at(const std::string& trace, const std::string& options) {
  const RunResult r = run_vbsim("replay " + trace + " " + options);
  return r.output.substr(r.output.find("verdicts"), r.output.find('\n', r.output.find("verdicts")) - r.output.find("verdicts"));
}

}  // namespace

TEST_CASE("fit brackets the tmin a hand-built trace needs", "[system][fit]") {
  const auto dir = scratch_dir("fit_tmin");
  const std::string trace = two_plane_trace(dir, kChildBelowParent);
  const json report = fit_json(trace + " --params tmin-eps", dir);
  REQUIRE(report["fits"].size() == 1);
  const json& f = report["fits"][0];
  CHECK(f["key"] == "tmin-eps");
  CHECK(f["rays"] == 2);
  REQUIRE(f["feasible"] == true);
  const double lowest = f["smallest"]["value"], below = f["smallest"]["below"], step = f["grid_step"];
  // The self hit lies at t = 0.001 (float 0.001 below the plane): the bound brackets it
  // within one grid step.
  CHECK(below < 0.001 * (1 + 1e-6));
  CHECK(lowest >= 0.001 * (1 - 1e-6));
  CHECK(lowest / below - 1 <= step * (1 + 1e-9));
  CHECK(f["smallest"]["ray"]["id"] == 1);
  // The upper end brackets the distance to Q, 1.001.
  const double highest = f["largest"]["value"], above = f["largest"]["above"];
  CHECK(highest < 1.001 * (1 + 1e-6));
  CHECK(above >= 1.001 * (1 - 1e-6));
  CHECK(f["largest"]["ray"]["id"] == 1);
  CHECK(f["check"]["passed"] == true);
  CHECK(f["check"]["below_self_hit"] == 1);
  // Replaying at the value found gives no error; one grid step below, a self hit.
  CHECK(verdicts_at(trace, fmt_double_option("--method tmin --tmin-eps", lowest)) ==
        "verdicts  correct 2 self_hit 0 false_hit 0 missed 0 unscored 0");
  CHECK(verdicts_at(trace, fmt_double_option("--method tmin --tmin-eps", below)) ==
        "verdicts  correct 1 self_hit 1 false_hit 0 missed 0 unscored 0");
}

TEST_CASE("fit says none exists and names the two rays that prove it", "[system][fit]") {
  const auto dir = scratch_dir("fit_none");
  // Ray 2 starts 0.5 below P (tmin must exceed 0.5); ray 3, a camera ray 0.2 below
  // Q, must see Q (tmin must stay below 0.2).
  const std::string trace = two_plane_trace(
      dir, std::string(kChildBelowParent) +
               "{\"id\":2,\"parent\":0,\"kind\":\"refract\",\"o\":[0.5,0,-0.5],\"d\":[0,0,1],\"parent_prim\":0}\n"
               "{\"id\":3,\"o\":[1,0,0.8],\"d\":[0,0,1]}\n");
  const json report = fit_json(trace + " --params tmin-eps", dir);
  REQUIRE(report["fits"].size() == 1);
  for (const json& f : report["fits"]) {
    INFO(f.dump(1));
    CHECK(f["feasible"] == false);
    CHECK(f["smallest"]["ray"]["id"] == 2);
    CHECK(f["largest"]["ray"]["id"] == 3);
    // Ray 2 self-hits at `below` (just under 0.5), ray 3 is missed at `above` (just
    // over 0.2), each within one grid step, and above <= below: no value works.
    const double below = f["smallest"]["below"], above = f["largest"]["above"], step = f["grid_step"];
    CHECK(below < 0.5);
    CHECK(below >= 0.5 / (1 + step) * (1 - 1e-6));
    CHECK(above >= 0.2 * (1 - 1e-6));
    CHECK(above <= 0.2 * (1 + step) * (1 + 1e-6));
    CHECK(above <= below);
  }
  const RunResult r = run_vbsim("fit " + trace + " --params tmin-eps");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("none exists") && Catch::Contains("ray 2 (refract) self-hits") &&
                           Catch::Contains("ray 3 (primary) is missed"));
}

TEST_CASE("fit finds the validity-bit epsilon and guard band on the bundled trace", "[system][fit]") {
  const auto dir = scratch_dir("fit_bunny");
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const json report = fit_json(trace + " --params vb-eps,vb-guard-bits", dir);
  for (const json& f : report["fits"]) {
    INFO(f.dump(1));
    REQUIRE(f["feasible"] == true);
    CHECK(f["check"]["passed"] == true);
    CHECK(f["check"]["below_self_hit"].get<int>() >= 1);
  }
  // Cross-check by replay: the fitted guard band has no self hit, one bit less has one.
  const int guard = report["fits"][1]["smallest"]["value"].get<int>();
  const std::string opts = " -m validity-bit --vb-eps-mode exponent --vb-min-exponent 1 --vb-guard-bits ";
  CHECK_THAT(verdicts_at(trace, opts + std::to_string(guard)), Catch::Contains("self_hit 0 ") && Catch::Contains("missed 0 "));
  CHECK_THAT(verdicts_at(trace, opts + std::to_string(guard - 1)), !Catch::Contains("self_hit 0 "));
}

TEST_CASE("fit rejects bad input with a clear message", "[system][fit][errors]") {
  const auto dir = scratch_dir("fit_errors");
  const std::string bunny = source_dir() + "/traces/bunny";
  write_file(dir / "planes.obj", kTwoPlanes);
  write_file(dir / "noexpect.jsonl", "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"planes.obj\"}\n"
                                     "{\"id\":0,\"o\":[0,0,-5],\"d\":[0,0,1]}\n");
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"fit " + (dir / "missing.jsonl").string(), "no such trace file or directory"},
      {"fit " + bunny + " --params tmin-eps,epsilon", "unknown fit parameter 'epsilon'"},
      {"fit " + bunny + " --tester slab", "unknown tester 'slab'"},
      {"fit " + bunny + " --vb-policy most", "unknown policy 'most'"},
      {"fit " + bunny + " --vb-min-exponent 0", "--vb-min-exponent"},
      {"fit " + (dir / "noexpect.jsonl").string(), "no ray has `expect`"},
      {"fit", "paths is required"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_vbsim(c.args);
    INFO(c.args << "\n" << r.output);
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.output, Catch::Contains(c.message));
  }
}
