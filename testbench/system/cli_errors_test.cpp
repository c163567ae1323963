// Bad input through the vbsim program: a clear error naming file, line and
// field, a non-zero exit, never a crash.
#include <catch2/catch.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {
std::string header_line() {
  return "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"" + source_dir() +
         "/traces/bunny/bunny.obj\"}\n";
}
}  // namespace

TEST_CASE("replay of a trace with a zero direction names file, line and field", "[cli]") {
  const auto dir = scratch_dir("zero_dir");
  write_file(dir / "t.jsonl", header_line() + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n" +
                                  "# a comment\n{\"id\":1,\"o\":[0,0,5],\"d\":[0,0,0]}\n");
  const RunResult r = run_vbsim("replay " + (dir / "t.jsonl").string());
  CHECK(r.exit_code != 0);
  CHECK(r.exit_code < 128);  // an error exit, not a signal or abort
  CHECK_THAT(r.output, Catch::Contains("t.jsonl:4") && Catch::Contains("'d'"));
}

TEST_CASE("replay rejects a triangle index out of range for the scene", "[cli]") {
  const auto dir = scratch_dir("prim_range");
  write_file(dir / "t.jsonl",
             header_line() + "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1],\"parent_prim\":99999}\n");
  const RunResult r = run_vbsim("replay " + (dir / "t.jsonl").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("t.jsonl:2") && Catch::Contains("parent_prim"));
}

TEST_CASE("replay reports a missing scene file by name", "[cli]") {
  const auto dir = scratch_dir("no_scene");
  write_file(dir / "t.jsonl", "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"nothere.obj\"}\n");
  const RunResult r = run_vbsim("replay " + (dir / "t.jsonl").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("nothere.obj"));
}

TEST_CASE("unknown method and bad config fields are named", "[cli]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  RunResult r = run_vbsim("replay " + trace + " --method offset-adaptive+bogus");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("bogus"));
  const auto dir = scratch_dir("bad_config");
  write_file(dir / "c.json", "{\"validity_bit\": {\"guard_bits\": 99}}");
  r = run_vbsim("replay " + trace + " --config " + (dir / "c.json").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("c.json") && Catch::Contains("validity_bit.guard_bits"));
  write_file(dir / "c.json", "{\"validity_bit\": {\"gaurd_bits\": 4}}");
  r = run_vbsim("replay " + trace + " --config " + (dir / "c.json").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("validity_bit.gaurd_bits") && Catch::Contains("unknown field"));
}

TEST_CASE("a truncated rtcore ray file is an error naming the partial record", "[cli]") {
  const auto dir = scratch_dir("rtcore_partial");
  write_file(dir / "rays.bin", std::string(28 * 2 + 5, '\0'));
  const RunResult r = run_vbsim("convert " + (dir / "rays.bin").string() + " --from rtcore --scene " +
                                source_dir() + "/traces/bunny/bunny.obj -o " + (dir / "o.jsonl").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("rays.bin") && Catch::Contains("record 2"));
}
