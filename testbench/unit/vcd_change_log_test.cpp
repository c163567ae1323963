// VcdChangeLog: changes added in any order come back in cycle order, the same
// whether they stayed in memory or were spilled to its temporary file in
// small chunks; and a VCD written through spilled chunks is byte for byte the
// one written from memory.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <tuple>
#include <vector>

#include "hw/observe/vcd_change_log.h"
#include "hw/observe/vcd_recorder.h"

using namespace vbsim::hw;

namespace {
using Key = std::tuple<uint64_t, uint32_t, int64_t>;

std::vector<Key> read_all(VcdChangeLog& log) {
  std::vector<Key> out;
  VcdChangeLog::Change c{};
  while (log.next(c)) out.emplace_back(c.cycle, c.id, c.delta);
  return out;
}
}  // namespace

TEST_CASE("VCD changes come back in cycle order from memory and from spilled runs", "[unit][tracing]") {
  std::mt19937_64 rng(7);
  std::vector<Key> added;
  for (int i = 0; i < 10000; ++i)
    added.emplace_back(rng() % 500, static_cast<uint32_t>(rng() % 9), static_cast<int64_t>(rng() % 5) - 2);
  for (const size_t chunk : {size_t{1} << 20, size_t{1}, size_t{7}, size_t{4096}, size_t{5000}}) {
    INFO("chunk " << chunk);
    VcdChangeLog log(chunk);
    for (const auto& [cycle, id, delta] : added) log.add({cycle, id, delta});
    std::vector<Key> got = read_all(log);
    CHECK((chunk >= added.size() ? log.spilled_runs() == 1 : log.spilled_runs() > 1));
    REQUIRE(got.size() == added.size());
    CHECK(std::is_sorted(got.begin(), got.end(),
                         [](const Key& a, const Key& b) { return std::get<0>(a) < std::get<0>(b); }));
    std::vector<Key> want = added;
    std::sort(want.begin(), want.end());
    std::sort(got.begin(), got.end());
    CHECK(got == want);  // every change once
  }
  VcdChangeLog empty;
  CHECK(read_all(empty).empty());
}

TEST_CASE("a VCD written from spilled changes equals one written from memory", "[unit][tracing]") {
  const auto dir = std::filesystem::temp_directory_path() / ("vbsim_vcd_spill_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::mt19937_64 rng(3);
  std::vector<Key> added;
  for (int i = 0; i < 3000; ++i) {
    const uint64_t at = rng() % 1000, len = 1 + rng() % 40;
    const uint32_t id = static_cast<uint32_t>(rng() % 3);
    added.emplace_back(at, id, 1);
    added.emplace_back(at + len, id, -1);
  }
  std::string text[2];
  for (int k = 0; k < 2; ++k) {
    VcdRecorder v(100, 800, 2000, TraceScope(), k == 0 ? size_t{1} << 20 : size_t{13});
    const uint32_t ids[3] = {v.signal("accelerator.core_0", "a"), v.signal("accelerator.core_0", "b"),
                             v.signal("accelerator.l2_cache", "c")};
    for (const auto& [cycle, id, delta] : added) v.add(ids[id], cycle, delta);
    const auto path = dir / ("v" + std::to_string(k) + ".vcd");
    v.write(path.string(), 850);
    std::ostringstream s;
    s << std::ifstream(path).rdbuf();
    text[k] = s.str();
  }
  CHECK(text[0].size() > 1000);
  CHECK(text[0] == text[1]);
  std::filesystem::remove_all(dir);
}
