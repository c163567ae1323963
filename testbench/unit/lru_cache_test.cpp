// The LRU tag array: eviction order by hand on a tiny cache, and the hit/miss
// sequence of random streams against an explicit most-recent-first list per set.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "hw/lru_cache.h"
#include "lru_reference.h"

using vbsim::hw::LruCache;

namespace {

bool access(LruCache& c, uint64_t line) {
  if (c.touch(line)) return true;
  c.install(line);
  return false;
}

}  // namespace

TEST_CASE("LRU cache evicts the least recently used line of a 2-way set", "[memory][lru]") {
  LruCache c(2, 2);  // lines 0, 2, 4 share set 0
  CHECK(c.install(0) == LruCache::kNoLine);
  CHECK(c.install(2) == LruCache::kNoLine);
  CHECK(c.touch(0));             // 0 is now more recent than 2
  CHECK(c.install(4) == 2);      // so 2 goes
  CHECK(c.contains(0));
  CHECK_FALSE(c.contains(2));
  CHECK(c.install(6) == 0);      // 0 is older than 4
  CHECK(c.contains(4));
  CHECK(c.contains(6));
  CHECK(c.install(1) == LruCache::kNoLine);  // set 1 is untouched by set 0's traffic
  CHECK(c.contains(4));
}

TEST_CASE("LRU cache contains does not change the replacement order", "[memory][lru]") {
  LruCache c(1, 2);
  c.install(10);
  c.install(11);
  CHECK(c.contains(10));  // no touch: 10 stays least recent
  CHECK(c.install(12) == 10);
}

TEST_CASE("LRU cache matches an explicit LRU list on random streams", "[memory][lru]") {
  struct Shape { uint32_t sets, ways; };
  for (const Shape shape : {Shape{1, 4}, Shape{4, 2}, Shape{8, 4}, Shape{3, 3}, Shape{16, 1}}) {
    LruCache cache(shape.sets, shape.ways);
    ListLru reference(shape.sets, shape.ways);
    std::mt19937_64 rng(shape.sets * 131 + shape.ways);
    // Half the accesses to a hot range that mostly fits, half to a wide range: both hits and misses.
    const uint64_t hot = uint64_t{shape.sets} * shape.ways + 2;
    std::uniform_int_distribution<uint64_t> hot_line(0, hot - 1), cold_line(0, 40 * hot);
    size_t hits = 0;
    for (int i = 0; i < 4000; ++i) {
      const uint64_t line = (rng() & 1) ? hot_line(rng) : cold_line(rng);
      const bool expected = reference.access(line);
      INFO("sets " << shape.sets << " ways " << shape.ways << " access " << i << " line " << line);
      REQUIRE(access(cache, line) == expected);
      hits += expected;
    }
    CHECK(hits > 400);   // the stream exercised both outcomes
    CHECK(hits < 3600);
  }
}
