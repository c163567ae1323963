// The embedding example (testbench/examples/embed_accelerator.cpp): a user's
// own sc_main with a memory target of its own runs the bundled trace. Its rays
// and hits are those of `vbsim replay`, its target served every read the L2
// sent, SystemC time ran as its cycles times the clock period, and a slower
// target gives a longer run.
#include <catch2/catch.hpp>

#include <cstdio>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

/// "key value" lines of the example's output, run on the bundled trace with a
/// memory of `latency` cycles.
std::map<std::string, std::string> run_example(unsigned latency) {
  const std::string cmd = std::string("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1 ") + VBSIM_EMBED_EXAMPLE + " " +
                          source_dir() + "/traces/bunny/paths.jsonl " + std::to_string(latency) + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe);
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  INFO(out);
  REQUIRE(pclose(pipe) == 0);
  std::map<std::string, std::string> f;
  std::istringstream in(out);
  std::string key, value;
  while (in >> key >> value) f[key] = value;
  REQUIRE(f.count("cycles"));
  return f;
}

uint64_t num(const std::map<std::string, std::string>& f, const char* key) { return std::stoull(f.at(key)); }

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
  CHECK(num(slow, "hits") == num(fast, "hits"));

  const auto dir = scratch_dir("embed");
  const auto r = run_vbsim("replay " + source_dir() + "/traces/bunny/paths.jsonl -m validity-bit --stats " +
                           (dir / "s.json").string() + " -q");
  REQUIRE(r.exit_code == 0);
  const auto s = nlohmann::json::parse(read_file(dir / "s.json"));
  CHECK(s["hits"].get<uint64_t>() == num(fast, "hits"));
  CHECK(s["rays"].get<uint64_t>() == num(fast, "rays"));
}
