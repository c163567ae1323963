// vbsim check, and the same checks inside replay (both modes), oracle and
// convert: a child before its parent is an error naming the line; the other
// checks are warnings, listed by check and counted by the others.
#include <catch2/catch.hpp>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

std::string header_line() {
  return "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"" + source_dir() + "/traces/bunny/bunny.obj\"}\n";
}

/// Line 2 of the bundled bunny trace: a camera ray with its expected answer.
std::string bunny_camera_ray() {
  const std::string all = read_file(source_dir() + "/traces/bunny/paths.jsonl");
  const std::size_t first = all.find('\n') + 1;
  return all.substr(first, all.find('\n', first) - first + 1);
}

}  // namespace

TEST_CASE("check names every problem with its line and exits 1 on an error", "[cli][check]") {
  const auto dir = scratch_dir("check_problems");
  // Line 2: ray 0 fine (from the bundled trace); line 3: ray 5 whose parent 9
  // comes later; line 4: ray 4 (id out of order); lines 5-6: no expect.
  const std::string camera = bunny_camera_ray();
  REQUIRE(camera.find("\"id\":0") != std::string::npos);
  write_file(dir / "t.jsonl", header_line() + camera +
                                  "{\"id\":5,\"parent\":9,\"kind\":\"diffuse\",\"o\":[0,0,5],\"d\":[0,0,-1],\"parent_prim\":3,\"expect\":{\"prim\":-1}}\n" +
                                  "{\"id\":4,\"o\":[0,0,5],\"d\":[0,0,-1],\"expect\":{\"prim\":-1}}\n" +
                                  "{\"id\":6,\"o\":[0,0,5],\"d\":[0,0,-1]}\n{\"id\":7,\"o\":[0,0,5],\"d\":[0,0,-1]}\n");
  const RunResult r = run_vbsim("check " + (dir / "t.jsonl").string());
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("t.jsonl:3: error [child_before_parent]: field 'parent'"));
  CHECK_THAT(r.output, Catch::Contains("t.jsonl:4: warning [id_order]"));
  CHECK_THAT(r.output, Catch::Contains("t.jsonl:5-6: warning [missing_expect]") &&
                           Catch::Contains("2 rays") && Catch::Contains("vbsim oracle"));
  CHECK_THAT(r.output, Catch::Contains("5 rays, 1 error, 3 warnings"));
}

TEST_CASE("check reports format errors line by line and keeps going", "[cli][check]") {
  const auto dir = scratch_dir("check_format");
  write_file(dir / "t.jsonl", header_line() + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,0]}\n" +
                                  "{\"id\":1,\"o\":[0,0,5],\"d\":[0,0,-1],\"expect\":{\"prim\":-1}}\n" +
                                  "{\"id\":1,\"o\":[0,0,5],\"d\":[0,0,-1]}\n");
  const RunResult r = run_vbsim("check " + (dir / "t.jsonl").string());
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("t.jsonl:2: field 'd': direction is zero"));
  CHECK_THAT(r.output, Catch::Contains("t.jsonl:4: field 'id': duplicate id 1"));
  CHECK_THAT(r.output, Catch::Contains("1 ray, 2 errors"));
}

TEST_CASE("check passes the bundled trace and every generated scenario", "[cli][check]") {
  RunResult r = run_vbsim("check --strict " + source_dir() + "/traces/bunny/paths.jsonl");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("1008 rays, 0 errors, 0 warnings"));
  const auto dir = scratch_dir("check_scenarios");
  for (const char* name : {"paths", "random-triangles", "grazing", "shared-edges", "crevice", "corner", "layers",
                           "coplanar", "far-instance", "refraction", "terminator"}) {
    const auto out = dir / name;
    REQUIRE(run_vbsim(std::string("gen ") + name + " --rays 12 -o " + out.string()).exit_code == 0);
    int traces = 0;
    for (const auto& entry : std::filesystem::directory_iterator(out)) {
      if (entry.path().extension() != ".jsonl") continue;
      ++traces;
      r = run_vbsim("check --strict " + entry.path().string());
      INFO(entry.path() << ": " << r.output);
      CHECK(r.exit_code == 0);
      CHECK_THAT(r.output, Catch::Contains(" 0 errors, 0 warnings"));
    }
    CHECK(traces > 0);
  }
}

TEST_CASE("replay, oracle and convert refuse a child before its parent, naming the line", "[cli][check]") {
  const auto dir = scratch_dir("check_in_commands");
  write_file(dir / "t.jsonl", header_line() + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n" +
                                  "{\"id\":1,\"parent\":2,\"kind\":\"reflect\",\"o\":[0,0,5],\"d\":[0,0,1],\"parent_prim\":0}\n" +
                                  "{\"id\":2,\"o\":[0,0,5],\"d\":[0,0,-1]}\n");
  const std::string t = (dir / "t.jsonl").string();
  for (const std::string& cmd : {"replay " + t, "replay --mode cycle " + t, "oracle " + t + " -o " + (dir / "o.jsonl").string(),
                                "convert " + t + " -o " + (dir / "c.vbt").string()}) {
    const RunResult r = run_vbsim(cmd);
    INFO(cmd << ": " << r.output);
    CHECK(r.exit_code != 0);
    CHECK(r.exit_code < 128);
    CHECK_THAT(r.output, Catch::Contains("t.jsonl:3: field 'parent'") && Catch::Contains("child before parent"));
  }
}

TEST_CASE("replay counts the warnings into its statistics and reports them on stderr", "[cli][check]") {
  const auto dir = scratch_dir("check_warnings");
  // A shadow ray from the bundled trace's first hit with its sign bit flipped.
  const std::string all = read_file(source_dir() + "/traces/bunny/paths.jsonl");
  std::string out = header_line();  // the scene by absolute path
  std::size_t at = all.find('\n') + 1, flipped = 0;
  while (at < all.size()) {
    const std::size_t end = all.find('\n', at);
    std::string line = all.substr(at, end - at + 1);
    if (flipped == 0 && line.find("\"sign\":0") != std::string::npos) {
      line.replace(line.find("\"sign\":0"), 8, "\"sign\":1");
      ++flipped;
    }
    out += line;
    at = end + 1;
  }
  REQUIRE(flipped == 1);
  write_file(dir / "t.jsonl", out);
  const RunResult r = run_vbsim("replay " + (dir / "t.jsonl").string() + " --stats " + (dir / "s.json").string());
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("warning: 1 ray: a sign bit that contradicts"));
  const nlohmann::json stats = nlohmann::json::parse(read_file(dir / "s.json"));
  CHECK(stats["checks"]["warnings"]["sign"] == 1);
  CHECK(stats["checks"]["warnings"]["parent_data"] == 0);
  CHECK(stats["rays"] == 1008);
}
