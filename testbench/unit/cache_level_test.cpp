// CacheLevel against a plain model of the rules in docs/memory-model.md: tag
// sets as explicit lists of (line, fill cycle), most recent first, a line
// allocated when its miss is sent in the way of the least recent line not in
// flight; every MSHR's free cycle scanned for the earliest. Random streams with fills far out of order (an L2 hit next to a
// DRAM miss), so lines are looked up while in flight, MSHRs run full and equal
// fill cycles tie; and a hand-computed case.
#include <catch2/catch.hpp>

#include <algorithm>
#include <list>
#include <random>
#include <utility>
#include <vector>

#include "hw/memory/cache_level.h"

using namespace vbsim::hw;

namespace {

class PlainLevel {
 public:
  PlainLevel(uint32_t sets, uint32_t ways, uint32_t hit_latency, uint32_t mshrs)
      : sets_(sets), ways_(ways), hit_latency_(hit_latency), free_(mshrs, 0) {}

  CacheLevel::Access access(uint64_t line, uint64_t t) {
    auto& set = sets_[line % sets_.size()];
    const auto it = std::find_if(set.begin(), set.end(), [&](const auto& way) { return way.first == line; });
    if (it != set.end()) {
      set.splice(set.begin(), set, it);
      const uint64_t fill = set.front().second;
      return t < fill ? CacheLevel::Access{CacheLevel::Outcome::Merge, fill, 0}
                      : CacheLevel::Access{CacheLevel::Outcome::Hit, t + hit_latency_, 0};
    }
    const uint64_t earliest = *std::min_element(free_.begin(), free_.end());
    return {CacheLevel::Outcome::Miss, 0, std::max(t, earliest)};
  }
  void fill(uint64_t line, uint64_t fill, uint64_t start) {
    auto& set = sets_[line % sets_.size()];
    if (set.size() == ways_) {  // full: the least recent way not in flight at start, else the least recent
      auto victim = std::prev(set.end());
      for (auto it = set.rbegin(); it != set.rend(); ++it)
        if (it->second <= start) {
          victim = std::prev(it.base());
          break;
        }
      set.erase(victim);
    }
    set.push_front({line, fill});
    *std::min_element(free_.begin(), free_.end()) = fill;  // the MSHR the miss took
  }

 private:
  std::vector<std::list<std::pair<uint64_t, uint64_t>>> sets_;
  size_t ways_;
  uint32_t hit_latency_;
  std::vector<uint64_t> free_;
};

struct Shape {
  uint32_t sets, ways, mshrs;
};

/// Drives a CacheLevel (its lookups and fills compiled for `Ways` ways, 0: read
/// at run time) and the plain model with one random stream; every answer must agree.
template <uint32_t Ways>
void check_against_plain(const Shape shape) {
  const uint32_t hit_latency = 2;
  CacheLevel level(CacheConfig{shape.sets * shape.ways * 64, shape.ways, 64, hit_latency, shape.mshrs});
  PlainLevel plain(shape.sets, shape.ways, hit_latency, shape.mshrs);
  std::mt19937_64 rng(shape.sets * 1000 + shape.mshrs);
  std::uniform_int_distribution<uint64_t> line_of(0, 3 * uint64_t{shape.sets} * shape.ways);
  std::uniform_int_distribution<int> step(0, 1), near_far(0, 3), near(1, 20), far(100, 130);
  uint64_t t = 0, misses = 0, merges = 0, waits = 0;
  for (int i = 0; i < 20000; ++i) {
    t += static_cast<uint64_t>(step(rng));
    const uint64_t line = line_of(rng);
    const CacheLevel::Access got = level.access<Ways>(line, t), want = plain.access(line, t);
    INFO("shape " << shape.sets << "x" << shape.ways << " mshrs " << shape.mshrs << " compiled ways " << Ways
                  << " request " << i);
    REQUIRE(got.outcome == want.outcome);
    if (got.outcome != CacheLevel::Outcome::Miss) {
      REQUIRE(got.ready == want.ready);
      merges += got.outcome == CacheLevel::Outcome::Merge;
      continue;
    }
    REQUIRE(got.start == want.start);
    ++misses;
    waits += got.start > t;
    // Fills far out of order, and equal fill cycles now and then.
    const uint64_t fill = got.start + hit_latency + static_cast<uint64_t>(near_far(rng) ? near(rng) : far(rng));
    level.template fill<Ways>(line, fill, got.start);
    plain.fill(line, fill, got.start);
  }
  const LevelCounters c = level.counters();
  CHECK(c.misses == misses);
  CHECK(c.merges == merges);
  CHECK(c.accesses == 20000);
  CHECK(misses > 1000);  // the stream exercised misses, merges and full MSHRs
  CHECK(merges > 100);
  CHECK(waits > 100);
}

}  // namespace

TEST_CASE("Cache level allocates at the miss, keeps lines in flight, merges before the fill", "[memory][mshr]") {
  // 1 set of 2 ways, hit latency 2, 2 MSHRs.
  CacheLevel level(CacheConfig{2 * 64, 2, 64, 2, 2});
  using O = CacheLevel::Outcome;
  CacheLevel::Access a = level.access(7, 10);
  CHECK((a.outcome == O::Miss && a.start == 10));
  level.fill(7, 50, a.start);
  a = level.access(7, 20);  // in flight: merges, ready at its fill
  CHECK((a.outcome == O::Merge && a.ready == 50));
  a = level.access(8, 21);
  CHECK((a.outcome == O::Miss && a.start == 21));
  level.fill(8, 40, a.start);
  a = level.access(9, 22);  // both MSHRs held, the first frees at 40
  CHECK((a.outcome == O::Miss && a.start == 40));
  level.fill(9, 90, a.start);  // at 40, 7 (least recent) is in flight, 8 has filled: 8 goes
  a = level.access(7, 60);
  CHECK((a.outcome == O::Hit && a.ready == 62));
  a = level.access(8, 61);
  CHECK((a.outcome == O::Miss && a.start == 61));  // MSHRs free at 50 and 90
  level.fill(8, 150, a.start);  // 9 (least recent now) is in flight until 90: 7 goes
  a = level.access(10, 62);
  CHECK((a.outcome == O::Miss && a.start == 90));
  level.fill(10, 200, a.start);  // 9 filled at 90: it goes
  a = level.access(8, 95);
  CHECK((a.outcome == O::Merge && a.ready == 150));
  const LevelCounters c = level.counters();
  CHECK(c.hits == 1);
  CHECK(c.merges == 2);
  CHECK(c.misses == 5);
  CHECK(c.accesses == 8);
  CHECK(c.mshr_stall_cycles == (40 - 22) + (90 - 62));
}

TEST_CASE("Cache level matches a plain model on random streams", "[memory][mshr]") {
  for (const Shape shape :
       {Shape{4, 2, 1}, Shape{4, 2, 3}, Shape{3, 4, 8}, Shape{16, 4, 8}, Shape{8, 8, 32}, Shape{8, 16, 16}})
    check_against_plain<0>(shape);
}

TEST_CASE("Cache level lookups compiled for 4 8 and 16 ways match the plain model", "[memory][mshr]") {
  // The forms the L1Cache and L2Cache modules use for the presets' associativities.
  check_against_plain<4>(Shape{3, 4, 8});
  check_against_plain<4>(Shape{16, 4, 8});
  check_against_plain<8>(Shape{8, 8, 32});
  check_against_plain<16>(Shape{8, 16, 16});
}
