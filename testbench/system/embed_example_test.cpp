// The embedding example (testbench/examples/embed_accelerator.cpp): a user's
// own sc_main with a memory target of its own runs the bundled trace. Its rays
// and hits are those of `vbsim replay`, its target served every read the L2
// sent, SystemC time ran as its cycles times the clock period, and a slower
// target gives a longer run.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "example_output.h"

using namespace vbsim::test;

namespace {

/// The example run on the bundled trace with a memory of `latency` cycles.
ExampleFields run_example(unsigned latency) {
  return run_example_program(VBSIM_EMBED_EXAMPLE, source_dir() + "/traces/bunny/paths.jsonl " + std::to_string(latency),
                             "cycles");
}

uint64_t num(const ExampleFields& f, const char* key) { return field_u64(f, key); }

}  // namespace

TEST_CASE("a user's sc_main with its own memory target runs the accelerator", "[system][embed]") {
  const auto fast = run_example(80), slow = run_example(400);
  for (const auto* f : {&fast, &slow}) {
    CHECK(num(*f, "rays") == 1008);
    CHECK(num(*f, "user_memory_reads") == num(*f, "l2_dram_requests"));
    CHECK(num(*f, "user_memory_reads") > 100);
    // The small preset's clock is 400 MHz: 2.5 ns a cycle.
    CHECK(std::stod(f->at("systemc_time_ns")) == Approx(2.5 * static_cast<double>(num(*f, "cycles"))));
  }
  CHECK(num(slow, "cycles") > num(fast, "cycles"));
  // The library prices the run: the slower memory's longer run leaks longer, the chip is the same.
  CHECK(std::stod(fast.at("energy_pj_per_ray")) > 0);
  CHECK(std::stod(slow.at("energy_pj_per_ray")) > std::stod(fast.at("energy_pj_per_ray")));
  CHECK(std::stod(slow.at("chip_mm2")) == std::stod(fast.at("chip_mm2")));
  CHECK(std::stod(fast.at("chip_mm2")) > 1);
  CHECK(num(slow, "hits") == num(fast, "hits"));

  const auto dir = scratch_dir("embed");
  const auto r = run_vbsim("replay " + source_dir() + "/traces/bunny/paths.jsonl -m validity-bit --stats " +
                           (dir / "s.json").string() + " -q");
  REQUIRE(r.exit_code == 0);
  const auto s = nlohmann::json::parse(read_file(dir / "s.json"));
  CHECK(s["hits"].get<uint64_t>() == num(fast, "hits"));
  CHECK(s["rays"].get<uint64_t>() == num(fast, "rays"));
}
