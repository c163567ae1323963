// The clocked-design example (testbench/examples/clocked_design.cpp): a user's
// design with a free-running sc_clock and a clocked module of its own beside
// the accelerator, which is set to sc_stop() at completion. sc_start() returns
// (the program ends), at the SystemC time of the last ray's finish; the
// completion event reached the user's thread once and the callback was called
// once, both at that time; the clock ran throughout; and the accelerator's
// cycles and hits are those of a plain `vbsim replay --mode cycle` of the same
// trace and preset. Stopped early, the run ends the simulation too, without
// a completion.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "example_output.h"

using namespace vbsim::test;

TEST_CASE("a design with its own clock stops at the accelerator's completion with a plain run's cycles",
          "[system][embed][completion]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("clocked_design");
  for (const std::string preset : {"small", "large"}) {
    INFO(preset);
    const ExampleFields f = run_example_program(VBSIM_CLOCKED_EXAMPLE, trace + " " + preset, "cycles");
    const uint64_t cycles = field_u64(f, "cycles");
    const double period_ns = field_double(f, "period_ns");
    CHECK(field_u64(f, "sc_start_returned") == 1);
    CHECK(field_u64(f, "partial") == 0);
    CHECK(field_u64(f, "rays") == 1008);
    CHECK(field_u64(f, "completion_callbacks") == 1);
    CHECK(field_u64(f, "completion_callback_cycles") == cycles);
    CHECK(field_u64(f, "completion_notifications") == 1);
    CHECK(field_double(f, "completion_time_ns") == Approx(period_ns * static_cast<double>(cycles)));
    // Stopped at completion, although the clock had more edges to come.
    CHECK(field_double(f, "systemc_time_ns") == Approx(period_ns * static_cast<double>(cycles)));
    // Rising edges at 0, 1, ..., cycles periods; the last one's process may
    // not run before sc_stop() takes effect in that time step.
    CHECK(field_u64(f, "clock_edges") >= cycles);
    CHECK(field_u64(f, "clock_edges") <= cycles + 1);
    CHECK(field_u64(f, "edges_with_progress") > 0);
    CHECK(field_u64(f, "rays_done_sampled") <= 1008);

    const auto stats = dir / (preset + ".json");
    const RunResult r = run_vbsim("replay " + trace + " -m validity-bit --mode cycle --preset " + preset +
                                  " --stats " + stats.string() + " -q");
    REQUIRE(r.exit_code == 0);
    const auto s = nlohmann::json::parse(read_file(stats));
    CHECK(s["hw"]["cycles"].get<uint64_t>() == cycles);
    CHECK(s["hits"].get<uint64_t>() == field_u64(f, "hits"));
  }
}

TEST_CASE("a design with its own clock stops when the accelerator's run is stopped early", "[system][embed][completion]") {
  const ExampleFields f =
      run_example_program(VBSIM_CLOCKED_EXAMPLE, source_dir() + "/traces/bunny/paths.jsonl small 100", "cycles");
  CHECK(field_u64(f, "sc_start_returned") == 1);
  CHECK(field_u64(f, "partial") == 1);
  CHECK(field_u64(f, "rays") >= 100);
  CHECK(field_u64(f, "rays") < 1008);
  CHECK(field_u64(f, "completion_callbacks") == 0);
  CHECK(field_u64(f, "completion_notifications") == 0);
}
