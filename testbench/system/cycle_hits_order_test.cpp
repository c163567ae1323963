// The cycle-level replay's --hits file is the functional replay's, line for
// line: rays finish out of order in the hardware model, the file lists them in
// trace order; every field (id, prim, t, u, v, front, rejected, reversed,
// verdict) is the same, none legitimately differs.
#include <catch2/catch.hpp>

#include <sstream>

#include "hw/sink/trace_order_buffer.h"
#include "run_vbsim.h"

using namespace vbsim::test;

TEST_CASE("cycle and functional hits files are identical line by line", "[system][cycle]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("cycle_hits_order");
  // Few slots and a shallow stack: rays overtake each other and spill.
  write_file(dir / "cfg.json", R"({"hw": {"cores": 2, "slots_per_core": 3, "stack_depth": 2}})");
  for (const std::string method : {"none", "validity-bit", "offset-normal+primid"}) {
    INFO(method);
    const std::string common = "replay " + trace + " -q -m " + method;
    RunResult f = run_vbsim(common + " --hits " + (dir / "f.hits").string());
    RunResult c = run_vbsim(common + " --mode cycle --hits " + (dir / "c.hits").string() + " --stats " +
                            (dir / "c.json").string());
    RunResult d = run_vbsim(common + " --mode cycle --config " + (dir / "cfg.json").string() + " --hits " +
                            (dir / "d.hits").string());
    REQUIRE(f.exit_code == 0);
    REQUIRE(c.exit_code == 0);
    REQUIRE(d.exit_code == 0);
    CHECK(c.output.empty());  // stderr is not a terminal: no progress line
    // The first line records the command line, which differs; every ray line is the same.
    const std::string functional = without_provenance(read_file(dir / "f.hits"));
    CHECK(std::count(functional.begin(), functional.end(), '\n') == 1008);
    CHECK(without_provenance(read_file(dir / "c.hits")) == functional);
    CHECK(without_provenance(read_file(dir / "d.hits")) == functional);
  }
}

TEST_CASE("trace order buffer writes lines in index order and holds only the ones ahead", "[cycle]") {
  std::ostringstream out;
  vbsim::hw::TraceOrderBuffer buffer(out);
  buffer.put(2, "c\n");
  buffer.put(1, "b\n");
  CHECK(out.str().empty());
  CHECK(buffer.held() == 3);
  buffer.put(0, "a\n");
  CHECK(out.str() == "a\nb\nc\n");
  CHECK(buffer.held() == 0);
  buffer.put(3, "d\n");
  buffer.put(5, "f\n");
  CHECK(out.str() == "a\nb\nc\nd\n");
  buffer.flush();  // index 4 never came (a stopped run): skipped
  CHECK(out.str() == "a\nb\nc\nd\nf\n");
  CHECK(buffer.next_index() == 6);
}
