// Data on stdout that does not arrive fails the run, and then none of the
// run's output files takes its name: outputs are renamed only once stdout has
// been flushed (io/atomic_output_file.h, held commits). An earlier file of the
// same name stays as it was, and no temporary is left.
#include <catch2/catch.hpp>

#include <filesystem>

#include "run_vbsim.h"

using namespace vbsim::test;
namespace fs = std::filesystem;

namespace {

const std::string kTrace = source_dir() + "/traces/bunny/paths.jsonl";
const std::string kBunny = source_dir() + "/traces/bunny/bunny.obj";

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("a failed standard output leaves none of the run's outputs", "[cli][outputs]") {
  const auto dir = scratch_dir("failed_stdout");
  struct Case {
    const char* name;
    std::string args;                  ///< writes the outputs below, and data on stdout
    std::vector<std::string> outputs;  ///< in `dir`
  };
  const std::string d = dir.string() + "/";
  const std::vector<Case> cases = {
      {"replay", "replay " + kTrace + " --stats " + d + "s.json --hits " + d + "h.jsonl", {"s.json", "h.jsonl"}},
      {"replay cycle", "replay " + kTrace + " --mode cycle --stats " + d + "s.json --vcd " + d + "w.vcd --timeline " + d +
                           "t.json",
       {"s.json", "w.vcd", "t.json"}},
      {"render", "render " + kBunny + " --size 8x6 -o " + d + "i.png --stats " + d + "s.json --trace-out " + d +
                     "t.jsonl",
       {"i.png", "s.json", "t.jsonl"}},
      {"score", "score " + kTrace + " --methods none --testers three-half-plane --out " + d + "o.json", {"o.json"}},
      {"hw", "hw --json " + d + "h.json", {"h.json"}},
  };
  for (const Case& c : cases) {
    for (const char* stdout_fault : {"> /dev/full", ">&-"}) {
      INFO(c.name << " " << stdout_fault);
      const RunResult r = run_vbsim_raw(c.args + " 2>&1 " + stdout_fault);  // stderr to the test
      CHECK(r.exit_code == 1);
      CHECK_THAT(r.output, Catch::Contains("vbsim: error: standard output: "));
      CHECK(entries(dir).empty());  // no output, no temporary
    }
    // An output already there stays as it was.
    INFO(c.name);
    for (const std::string& o : c.outputs) write_file(dir / o, "earlier");
    const RunResult r = run_vbsim_raw(c.args + " 2>&1 > /dev/full");
    CHECK(r.exit_code == 1);
    for (const std::string& o : c.outputs) CHECK(read_file(dir / o) == "earlier");
    for (const std::string& o : c.outputs) fs::remove(dir / o);
    CHECK(entries(dir).empty());
    // With stdout whole, the same run writes them all.
    REQUIRE(run_vbsim_raw(c.args + " > /dev/null 2>&1").exit_code == 0);
    for (const std::string& o : c.outputs) CHECK(fs::exists(dir / o));
    for (const std::string& o : c.outputs) fs::remove(dir / o);
  }
}

TEST_CASE("a capture whose stdout is closed leaves no trace", "[cli][outputs][capture]") {
  const auto dir = scratch_dir("failed_stdout_capture");
  const auto out = dir / "cap";
  const std::string app = VBSIM_CAPTURE_TEST_APP;
  const RunResult r = run_vbsim_raw("capture --allow-partial -o " + out.string() + " -- " + app + " 1 " +
                                    (dir / "a.txt").string() + " 2>&1 >&-");
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("vbsim: error: standard output: "));
  CHECK(entries(out).empty());
}
