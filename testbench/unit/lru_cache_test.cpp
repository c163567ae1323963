// The LRU tag array: eviction order by hand on a tiny cache, fill cycles that
// travel with their lines, lines in flight kept, and the hit/miss sequence and
// fill cycles of random streams (every line filled when it is installed)
// against an explicit most-recent-first list per set; a tag array sized far
// beyond the lines touched costs host memory for those only.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdio>
#include <random>
#include <unordered_map>
#include <vector>

#include "hw/memory/lru_cache.h"
#include "lru_reference.h"

using vbsim::hw::LruCache;

TEST_CASE("LRU cache evicts the least recently used line of a 2-way set", "[memory][lru]") {
  LruCache c(2, 2);  // lines 0, 2, 4 share set 0
  CHECK(c.install(0, 0, 0) == LruCache::kNoLine);
  CHECK(c.install(2, 0, 0) == LruCache::kNoLine);
  uint64_t fill = 0;
  CHECK(c.touch(0, fill));       // 0 is now more recent than 2
  CHECK(c.install(4, 0, 0) == 2);   // so 2 goes
  CHECK(c.contains(0));
  CHECK_FALSE(c.contains(2));
  CHECK(c.install(6, 0, 0) == 0);   // 0 is older than 4
  CHECK(c.contains(4));
  CHECK(c.contains(6));
  CHECK(c.install(1, 0, 0) == LruCache::kNoLine);  // set 1 is untouched by set 0's traffic
  CHECK(c.contains(4));
}

TEST_CASE("LRU cache contains does not change the replacement order", "[memory][lru]") {
  LruCache c(1, 2);
  c.install(10, 0, 0);
  c.install(11, 0, 0);
  CHECK(c.contains(10));  // no touch: 10 stays least recent
  CHECK(c.install(12, 0, 0) == 10);
}

TEST_CASE("LRU cache keeps each line's fill cycle with the line as it moves", "[memory][lru]") {
  LruCache c(1, 3);
  c.install(5, 100, 0);
  c.install(6, 200, 0);
  c.install(7, 300, 0);
  uint64_t fill = 0;
  CHECK(c.touch(5, fill));  // from the last way to the first
  CHECK(fill == 100);
  CHECK(c.install(8, 400, 0) == 6);
  CHECK(c.touch(7, fill));
  CHECK(fill == 300);
  CHECK(c.touch(8, fill));
  CHECK(fill == 400);
  CHECK_FALSE(c.touch(6, fill));
  CHECK(c.install(6, 500, 0) == 5);  // 5 is the least recent now
  CHECK(c.touch(6, fill));
  CHECK(fill == 500);
}

TEST_CASE("LRU cache keeps a line in flight and evicts the least recent line that has filled", "[memory][lru]") {
  LruCache c(1, 3);
  c.install(1, 100, 0);
  c.install(2, 50, 0);
  c.install(3, 10, 0);                // recency 3, 2, 1; fills 10, 50, 100
  CHECK(c.install(4, 200, 20) == 3);  // at 20 only 3 has filled: 1 and 2 keep their ways
  CHECK(c.install(5, 300, 30) == 1);  // 4, 2, 1 all in flight at 30: the least recent goes
  CHECK(c.install(6, 400, 60) == 2);  // 2 filled at 50
  CHECK(c.contains(4));
  CHECK(c.contains(5));
  CHECK(c.contains(6));
}

/// Random streams against ListLru, with `Ways` as the compiled associativity
/// (0: read at run time); a hit must return the fill cycle its line was installed with.
template <uint32_t Ways>
void check_against_lists(uint32_t sets, uint32_t ways) {
  LruCache cache(sets, ways);
  ListLru reference(sets, ways);
  std::unordered_map<uint64_t, uint64_t> installed_fill;
  std::mt19937_64 rng(sets * 131 + ways);
  // Half the accesses to a hot range that mostly fits, half to a wide range: both hits and misses.
  const uint64_t hot = uint64_t{sets} * ways + 2;
  std::uniform_int_distribution<uint64_t> hot_line(0, hot - 1), cold_line(0, 40 * hot);
  size_t hits = 0;
  for (uint64_t i = 0; i < 4000; ++i) {
    const uint64_t line = (rng() & 1) ? hot_line(rng) : cold_line(rng);
    const bool expected = reference.access(line);
    INFO("sets " << sets << " ways " << ways << " compiled " << Ways << " access " << i << " line " << line);
    uint64_t fill = ~uint64_t{0};
    const bool got = cache.touch_in<Ways>(cache.set_of(line), line, fill);
    REQUIRE(got == expected);
    if (got) {
      REQUIRE(fill == installed_fill.at(line));
      ++hits;
    } else {
      cache.install_in<Ways>(cache.set_of(line), line, 1000 + i, 1000 + i);  // every line filled
      installed_fill[line] = 1000 + i;
    }
  }
  CHECK(hits > 400);   // the stream exercised both outcomes
  CHECK(hits < 3600);
}

TEST_CASE("LRU cache matches an explicit LRU list on random streams", "[memory][lru]") {
  check_against_lists<0>(1, 4);
  check_against_lists<0>(4, 2);
  check_against_lists<0>(8, 4);
  check_against_lists<0>(3, 3);
  check_against_lists<0>(16, 1);
  check_against_lists<0>(4, 5);  // a set longer than a host line, not a whole number of them
  check_against_lists<0>(5, 7);  // a number of sets that is not a power of two
  check_against_lists<0>(1, 16);  // fully associative, as rtcore-systemc's 16-entry caches
  check_against_lists<0>(1, 2048);  // fully associative beyond the former 1024-way cap
  check_against_lists<4>(8, 4);  // the forms the hierarchy compiles for the presets
  check_against_lists<8>(4, 8);
  check_against_lists<16>(2, 16);
}

namespace {

/// Resident host memory of this process, in bytes (/proc/self/statm).
long resident_bytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  long size = 0, resident = 0;
  if (f) {
    if (std::fscanf(f, "%ld %ld", &size, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return resident * ::sysconf(_SC_PAGESIZE);
}

}  // namespace

TEST_CASE("LRU cache: a tag array far larger than the lines touched costs host memory for those only",
          "[memory][lru]") {
  // 2^24 sets of 4 ways: 1 GiB of ways, the tag array of a 4 GiB cache of 64-byte lines.
  const long before = resident_bytes();
  LruCache c(1u << 24, 4);
  uint64_t fill = 0;
  // Untouched sets read as empty; lines far apart are found in their own sets.
  for (uint64_t k = 0; k < 1000; ++k) {
    const uint64_t line = k * 16411 + (k << 26);
    CHECK_FALSE(c.touch(line, fill));
    CHECK(c.install(line, k, 0) == LruCache::kNoLine);
  }
  for (uint64_t k = 0; k < 1000; ++k) {
    REQUIRE(c.touch(k * 16411 + (k << 26), fill));
    CHECK(fill == k);
  }
  CHECK_FALSE(c.contains(LruCache::kNoLine - 1));
  const long grown = resident_bytes() - before;
  INFO("resident memory grew by " << grown << " bytes");
  CHECK(grown < (64l << 20));  // 1000 sets touched: at most 1000 pages, not 1 GiB
}
