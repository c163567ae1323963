// The command-line conventions every command follows (README "Conventions"):
// --version, exit codes 0/1/2, status on stderr and data on stdout, -q, and
// the option checks that were inconsistent between modes.
#include <catch2/catch.hpp>

#include <regex>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {
const std::string kTrace = source_dir() + "/traces/bunny/paths.jsonl";
}

TEST_CASE("the version option prints the version and the git revision and exits 0", "[cli]") {
  const SplitRun r = run_vbsim_split("--version");
  CHECK(r.exit_code == 0);
  CHECK(std::regex_match(r.out, std::regex(R"(vbsim \d+\.\d+\.\d+ \(revision [0-9a-z.\-]+\)\n)")));
}

TEST_CASE("usage errors exit 2, runtime errors 1, each said once on stderr", "[cli]") {
  for (const std::string& args : std::vector<std::string>{"replay", "replay " + kTrace + " --no-such-option", "no-such-command",
                                 "replay " + kTrace + " --mode fast", "replay " + kTrace + " --tester bogus",
                                 "replay " + kTrace + " --timeline-cycles 5", "replay " + kTrace + " --vb-eps -1",
                                 "gen nosuch -o x", "score " + kTrace + " --methods tmin:bad",
                                 "render x.obj -o y.png --size 0x0", "bench --rays 0"}) {
    INFO(args);
    const SplitRun r = run_vbsim_split(args);
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
    CHECK(!r.err.empty());
  }
  for (const std::string& args : std::vector<std::string>{"replay /no/such/trace.jsonl", "oracle /no/such.jsonl -o /tmp/x.jsonl",
                                 "score /no/such/dir", "render /no/such.obj -o /tmp/x.png"}) {
    INFO(args);
    const SplitRun r = run_vbsim_split(args);
    CHECK(r.exit_code == 1);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Catch::StartsWith("vbsim: error: ") && Catch::Contains("/no/such"));
  }
}

TEST_CASE("an unknown method lists the valid ones", "[cli]") {
  const SplitRun r = run_vbsim_split("replay " + kTrace + " -m foo");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("\"foo\"") && Catch::Contains("none, tmin, primid") &&
                        Catch::Contains("validity-bit") && Catch::Contains("reverse-shadow"));
}

TEST_CASE("the timeline window options need --mode cycle and --timeline, as --timeline does", "[cli][cycle]") {
  for (const std::string& opt : std::vector<std::string>{"--timeline-cycles 50", "--timeline-start 3", "--timeline t.json", "--vcd w.vcd"}) {
    INFO(opt);
    const SplitRun r = run_vbsim_split("replay " + kTrace + " " + opt);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("need '--mode cycle'"));
  }
  const SplitRun r = run_vbsim_split("replay " + kTrace + " --mode cycle --timeline-cycles 50");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("need '--timeline FILE'"));
}

TEST_CASE("status goes to stderr, data to stdout, and quiet silences both", "[cli]") {
  const auto dir = scratch_dir("streams");
  const std::string gen_dir = (dir / "gen").string();
  SplitRun r = run_vbsim_split("gen coplanar --rays 5 -o " + gen_dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.empty());
  CHECK_THAT(r.err, Catch::Contains("vbsim gen coplanar"));
  r = run_vbsim_split("convert " + gen_dir + "/coplanar.jsonl -o " + (dir / "c.vbt").string());
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.empty());
  CHECK_THAT(r.err, Catch::Contains("vbsim convert"));
  r = run_vbsim_split("oracle " + (dir / "c.vbt").string() + " -o " + (dir / "o.jsonl").string());
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.empty());
  CHECK_THAT(r.err, Catch::Contains("vbsim oracle"));
  for (const std::string& args : std::vector<std::string>{"gen coplanar --rays 5 -q -o " + gen_dir, "oracle -q " + (dir / "c.vbt").string() +
                                     " -o " + (dir / "o.jsonl").string()}) {
    r = run_vbsim_split(args);
    CHECK(r.exit_code == 0);
    CHECK((r.out + r.err).empty());
  }
  r = run_vbsim_split("replay " + kTrace);  // the summary is the data
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("verdicts"));
  CHECK(r.err.empty());
}

TEST_CASE("a quiet cycle-level run prints nothing, and SystemC never writes to stdout", "[cli][cycle]") {
  const auto dir = scratch_dir("systemc_quiet");
  const std::string run = "replay " + kTrace + " --mode cycle --vcd " + (dir / "w.vcd").string();
  SplitRun r = run_vbsim_split(run + " -q");
  REQUIRE(r.exit_code == 0);
  CHECK((r.out + r.err).empty());
  r = run_vbsim_split(run);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("rays/cycle"));
  CHECK(r.out.find("Info:") == std::string::npos);  // SystemC's messages go to stderr (the VCD is written by vbsim)
}
