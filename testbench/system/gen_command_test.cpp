// vbsim gen: deterministic output, settings checked by name.
#include <catch2/catch.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

TEST_CASE("gen writes the same files for the same seed and different ones for another", "[cli][gen]") {
  const auto dir = scratch_dir("gen_determinism");
  const std::string mesh = " --set scene=" + source_dir() + "/traces/bunny/bunny.obj";
  REQUIRE(run_vbsim("gen paths --rays 20 --seed 5" + mesh + " -o " + (dir / "a").string()).exit_code == 0);
  REQUIRE(run_vbsim("gen paths --rays 20 --seed 5" + mesh + " -o " + (dir / "b").string()).exit_code == 0);
  REQUIRE(run_vbsim("gen paths --rays 20 --seed 6" + mesh + " -o " + (dir / "c").string()).exit_code == 0);
  // The same rays; the header's provenance names each run's own command line.
  const std::string a = without_provenance(read_file(dir / "a" / "paths.jsonl"));
  CHECK(a.size() > 1000);
  CHECK(a == without_provenance(read_file(dir / "b" / "paths.jsonl")));
  CHECK(a != without_provenance(read_file(dir / "c" / "paths.jsonl")));
  // Every ray of a generated trace carries its exact expectation.
  size_t rays = 0, expects = 0;
  for (size_t p = a.find('\n'); p != std::string::npos; p = a.find('\n', p + 1)) {
    const size_t end = a.find('\n', p + 1);
    if (end == std::string::npos) break;
    ++rays;
    expects += a.substr(p, end - p).find("\"expect\"") != std::string::npos;
  }
  CHECK(rays > 20);
  CHECK(expects == rays);
}

TEST_CASE("gen names an unknown scenario, a setting typo and a bad value", "[cli][gen]") {
  const auto dir = scratch_dir("gen_errors");
  RunResult r = run_vbsim("gen nosuch -o " + dir.string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("nosuch") && Catch::Contains("paths"));
  r = run_vbsim("gen paths --rays 5 --set dpeth=2 -o " + dir.string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("dpeth"));
  r = run_vbsim("gen paths --rays 5 --set depth=two -o " + dir.string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("depth=two"));
  r = run_vbsim("gen paths --rays 5 --set depth -o " + dir.string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("key=value"));
}
