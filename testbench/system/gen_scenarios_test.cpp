// vbsim gen over the failure-case scenarios: the same seed gives the same
// files, another seed different ones, and a bad setting is named.
#include <catch2/catch.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

TEST_CASE("gen layers coplanar far-instance refraction and terminator are deterministic for a seed", "[cli][gen]") {
  const auto dir = scratch_dir("gen_scenarios");
  const std::pair<const char*, const char*> runs[] = {{"layers", "layers-sep0.5"},
                                                      {"coplanar", "coplanar"},
                                                      {"far-instance", "far-instance-k20"},
                                                      {"refraction", "refraction-box"},
                                                      {"terminator", "terminator-s8"}};
  for (const auto& [name, trace] : runs) {
    INFO(name);
    for (const char* sub : {"a", "b", "c"}) {
      const std::string seed = std::string(sub) == "c" ? "8" : "7";
      const auto out = dir / name / sub;
      REQUIRE(run_vbsim(std::string("gen ") + name + " --rays 20 --seed " + seed + " -o " + out.string()).exit_code == 0);
    }
    const std::string file = std::string(trace) + ".jsonl";
    const std::string a = without_provenance(read_file(dir / name / "a" / file));
    CHECK(a.size() > 500);
    CHECK(a == without_provenance(read_file(dir / name / "b" / file)));
    CHECK(a != without_provenance(read_file(dir / name / "c" / file)));
  }
}

TEST_CASE("gen scenarios name a bad list entry and an out-of-range setting", "[cli][gen]") {
  const auto dir = scratch_dir("gen_scenario_errors");
  const std::pair<const char*, const char*> bad[] = {{"layers --set separation=0.5,x", "separation=0.5,x"},
                                                     {"far-instance --set k=30", "--set k"},
                                                     {"terminator --set segments=7", "segments"},
                                                     {"refraction --set objects=cone", "cone"}};
  for (const auto& [args, named] : bad) {
    const RunResult r = run_vbsim(std::string("gen ") + args + " -o " + dir.string());
    INFO(args << ": " << r.output);
    CHECK(r.exit_code != 0);
    CHECK(r.output.find(named) != std::string::npos);
  }
}
