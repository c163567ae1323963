// Caches of any geometry in a cycle-level run: fully associative ones
// ("ways": "full", as rtcore-systemc's small caches) and set counts that are not
// powers of two. With one core and one slot the L1 sees the same line stream
// whatever its size, so a fully associative LRU cache is a stack algorithm: its
// misses never grow with its size, and once it holds the whole footprint they
// are the compulsory misses, one per distinct line (the L2's misses: its 1 MiB
// holds the footprint too). The hits never depend on the caches.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

struct Run {
  int64_t l1_misses = 0, l2_misses = 0, cycles = 0;
  std::string hits;
};

Run replay(const std::string& hw, const std::filesystem::path& dir) {
  write_file(dir / "c.json", R"({"hw": )" + hw + "}");
  const std::string stats = (dir / "s.json").string(), hits = (dir / "h.jsonl").string();
  const RunResult r = run_vbsim("replay -q " + source_dir() + "/traces/bunny/paths.jsonl --mode cycle --deps off " +
                                "-m validity-bit --config " + (dir / "c.json").string() + " --stats " + stats +
                                " --hits " + hits);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(read_file(stats));
  const nlohmann::json& port = j["hw"]["memory"]["port"];
  const std::string h = read_file(hits);
  return {port["l1"]["misses"].get<int64_t>(), port["l2"]["misses"].get<int64_t>(), j["hw"]["cycles"].get<int64_t>(),
          h.substr(h.find('\n'))};  // the lines after the header (its command differs)
}

std::string full_l1(int lines) {
  return R"({"cores": 1, "slots_per_core": 1, "memory": {"l1": {"ways": "full", "size_bytes": )" +
         std::to_string(lines * 64) + "}}}";
}

}  // namespace

TEST_CASE("a fully associative L1's misses fall with its size to one per distinct line", "[cli][hw][memory]") {
  const auto dir = scratch_dir("cache_geometry_full");
  const Run reference = replay(R"({"cores": 1, "slots_per_core": 1})", dir);
  int64_t previous = -1;
  for (const int lines : {16, 64, 256, 1024, 4096, 65536}) {
    INFO(lines << " lines");
    const Run r = replay(full_l1(lines), dir);
    CHECK(r.hits == reference.hits);
    if (previous >= 0) CHECK(r.l1_misses <= previous);
    previous = r.l1_misses;
    CHECK(r.l1_misses >= r.l2_misses);
  }
  // 65,536 lines hold the whole footprint: every L1 miss is a first touch.
  const Run largest = replay(full_l1(65536), dir);
  CHECK(largest.l1_misses == largest.l2_misses);
  CHECK(replay(full_l1(16), dir).l1_misses > 4 * largest.l1_misses);  // 16 lines thrash
}

TEST_CASE("caches whose set counts are not powers of two run and keep the hits", "[cli][hw][memory]") {
  const auto dir = scratch_dir("cache_geometry_sets");
  const Run reference = replay("{}", dir);
  // L1: 12 KiB of 4-way 64-byte sets (48 sets); L2: 768 KiB, 8 ways (1,536 sets).
  const Run odd = replay(R"({"memory": {"l1": {"size_bytes": 12288}, "l2": {"size_bytes": 786432}}})", dir);
  CHECK(odd.hits == reference.hits);
  CHECK(odd.l1_misses > 0);
  CHECK(odd.l2_misses > 0);
}
