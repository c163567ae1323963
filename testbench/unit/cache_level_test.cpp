// CacheLevel's miss registers against a plain model of the rules in
// docs/memory-model.md: every MSHR scanned for the line in flight and for the
// first of the earliest free cycle, due fills sorted by (fill, claim order),
// tag sets as explicit lists. Random streams with fills far out of order (an
// L2 hit next to a DRAM miss), so MSHRs are claimed while their line is still
// in flight, and equal fill cycles tie.
#include <catch2/catch.hpp>

#include <algorithm>
#include <list>
#include <random>
#include <vector>

#include "hw/cache_level.h"

using namespace vbsim::hw;

namespace {

class PlainLevel {
 public:
  PlainLevel(uint32_t sets, uint32_t ways, uint32_t hit_latency, uint32_t mshrs)
      : sets_(sets), ways_(ways), hit_latency_(hit_latency), mshrs_(mshrs) {}

  void retire(uint64_t horizon) {
    std::vector<size_t> due;
    for (size_t i = 0; i < mshrs_.size(); ++i)
      if (mshrs_[i].in_flight && mshrs_[i].fill <= horizon) due.push_back(i);
    std::sort(due.begin(), due.end(), [&](size_t a, size_t b) {
      return mshrs_[a].fill != mshrs_[b].fill ? mshrs_[a].fill < mshrs_[b].fill : mshrs_[a].order < mshrs_[b].order;
    });
    for (const size_t i : due) install(i);
  }
  CacheLevel::Access access(uint64_t line, uint64_t t) {
    std::list<uint64_t>& set = sets_[line % sets_.size()];
    const auto it = std::find(set.begin(), set.end(), line);
    if (it != set.end()) {
      set.splice(set.begin(), set, it);
      return {CacheLevel::Outcome::Hit, t + hit_latency_, 0, 0};
    }
    for (const Mshr& m : mshrs_)
      if (m.in_flight && m.line == line)
        return t < m.fill ? CacheLevel::Access{CacheLevel::Outcome::Merge, m.fill, 0, 0}
                          : CacheLevel::Access{CacheLevel::Outcome::Hit, t + hit_latency_, 0, 0};
    size_t best = 0;
    for (size_t i = 1; i < mshrs_.size(); ++i)
      if (mshrs_[i].fill < mshrs_[best].fill) best = i;
    return {CacheLevel::Outcome::Miss, 0, static_cast<uint32_t>(best), std::max(t, mshrs_[best].fill)};
  }
  void hold(uint32_t mshr, uint64_t line, uint64_t fill) {
    if (mshrs_[mshr].in_flight) install(mshr);
    mshrs_[mshr] = {line, fill, ++claims_, true};
  }

 private:
  struct Mshr {
    uint64_t line = 0, fill = 0, order = 0;
    bool in_flight = false;
  };
  void install(size_t i) {
    std::list<uint64_t>& set = sets_[mshrs_[i].line % sets_.size()];
    set.push_front(mshrs_[i].line);
    if (set.size() > ways_) set.pop_back();
    mshrs_[i].in_flight = false;
  }

  std::vector<std::list<uint64_t>> sets_;
  size_t ways_;
  uint32_t hit_latency_;
  std::vector<Mshr> mshrs_;
  uint64_t claims_ = 0;
};

}  // namespace

struct Shape {
  uint32_t sets, ways, mshrs;
};

/// Drives a CacheLevel (its lookups and holds compiled for `Ways` ways, 0: read
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
    level.retire(t);
    plain.retire(t);
    const CacheLevel::Access got = level.access<Ways>(line, t), want = plain.access(line, t);
    INFO("shape " << shape.sets << "x" << shape.ways << " mshrs " << shape.mshrs << " compiled ways " << Ways
                  << " request " << i);
    REQUIRE(got.outcome == want.outcome);
    if (got.outcome != CacheLevel::Outcome::Miss) {
      REQUIRE(got.ready == want.ready);
      merges += got.outcome == CacheLevel::Outcome::Merge;
      continue;
    }
    REQUIRE(got.mshr == want.mshr);
    REQUIRE(got.start == want.start);
    ++misses;
    waits += got.start > t;
    // Fills far out of order, and equal fill cycles now and then.
    const uint64_t fill = got.start + hit_latency + static_cast<uint64_t>(near_far(rng) ? near(rng) : far(rng));
    level.template hold<Ways>(line, fill);
    plain.hold(want.mshr, line, fill);
  }
  CHECK(level.counters().misses == misses);
  CHECK(misses > 1000);  // the stream exercised misses, merges and full MSHRs
  CHECK(merges > 100);
  CHECK(waits > 100);
}

TEST_CASE("Cache level MSHRs match a plain scan on random streams", "[memory][mshr]") {
  for (const Shape shape :
       {Shape{4, 2, 1}, Shape{4, 2, 3}, Shape{3, 4, 8}, Shape{16, 4, 8}, Shape{8, 8, 32}, Shape{8, 16, 16}})
    check_against_plain<0>(shape);
}

TEST_CASE("Cache level lookups compiled for 4 8 and 16 ways match the plain model", "[memory][mshr]") {
  // The forms MemoryHierarchy uses for the presets' associativities.
  check_against_plain<4>(Shape{3, 4, 8});
  check_against_plain<4>(Shape{16, 4, 8});
  check_against_plain<8>(Shape{8, 8, 32});
  check_against_plain<16>(Shape{8, 16, 16});
}
