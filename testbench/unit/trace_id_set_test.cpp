// TraceIdSet: exact membership while the ids fit in its ranges, whatever the
// order they come in; beyond, answers that are never wrong (Unknown where a
// merged range covers the id) in a fixed number of ranges.
#include <catch2/catch.hpp>

#include <random>
#include <limits>
#include <set>

#include "trace/trace_id_set.h"

using namespace vbsim;
using Membership = TraceIdSet::Membership;

namespace {

Membership truth(const std::set<int64_t>& ref, int64_t id) { return ref.count(id) ? Membership::Yes : Membership::No; }

}  // namespace

TEST_CASE("trace id set: duplicates are found in any order, from any first id", "[trace]") {
  const int64_t first = GENERATE(0, 1, 1000000007);
  const int order = GENERATE(0, 1, 2);
  std::mt19937_64 rng(static_cast<uint64_t>(first + order));
  TraceIdSet ids;
  std::set<int64_t> ref;
  for (int i = 0; i < 5000; ++i) {
    int64_t id = first + i;
    if (order == 1) id = first + (i ^ 5);                             // swapped neighbours
    if (order == 2) id = first + static_cast<int64_t>(rng() % 3000);  // repeats
    const Membership before = truth(ref, id);
    REQUIRE(ids.insert(id) == before);
    ref.insert(id);
    const int64_t probe = first + static_cast<int64_t>(rng() % 6000) - 10;
    REQUIRE(ids.contains(probe) == truth(ref, probe));
  }
  CHECK(ids.exact());
}

TEST_CASE("trace id set: ids in order from an outlying first id stay two ranges", "[trace]") {
  // The first ray's id far above the rest, then 0, 1, 2, ...: the case that
  // made the old record grow with the trace.
  TraceIdSet ids(16);
  REQUIRE(ids.insert(3000000) == Membership::No);
  for (int64_t id = 0; id < 200000; ++id) REQUIRE(ids.insert(id) == Membership::No);
  CHECK(ids.ranges() == 2);
  CHECK(ids.exact());
  CHECK(ids.insert(3000000) == Membership::Yes);
  CHECK(ids.insert(123456) == Membership::Yes);
  CHECK(ids.contains(200000) == Membership::No);
  CHECK(ids.contains(2999999) == Membership::No);
}

TEST_CASE("trace id set: ranges joined from both sides", "[trace]") {
  TraceIdSet ids;
  for (int64_t id : {10, 12, 14, 11, 13}) REQUIRE(ids.insert(id) == Membership::No);
  CHECK(ids.ranges() == 1);
  for (int64_t id : {9, 15}) REQUIRE(ids.insert(id) == Membership::No);
  CHECK(ids.ranges() == 1);
  for (int64_t id = 9; id <= 15; ++id) CHECK(ids.contains(id) == Membership::Yes);
  CHECK(ids.contains(8) == Membership::No);
  CHECK(ids.contains(16) == Membership::No);
}

TEST_CASE("trace id set: scattered ids keep at most max_ranges ranges and are never answered wrongly", "[trace]") {
  const int pattern = GENERATE(0, 1, 2);
  std::mt19937_64 rng(77 + pattern);
  constexpr std::size_t kMax = 64;
  TraceIdSet ids(kMax);
  std::set<int64_t> ref;
  int64_t unknown = 0;
  for (int i = 0; i < 20000; ++i) {
    int64_t id = 0;
    if (pattern == 0) id = 3 * int64_t{i} + 7;                                  // spread ids, ascending
    if (pattern == 1) id = static_cast<int64_t>(rng() % 100000);                // random, with repeats
    if (pattern == 2) id = (i % 2 == 0) ? i : 1000000 - static_cast<int64_t>(i);  // two fronts
    const Membership got = ids.insert(id);
    if (got == Membership::Unknown) ++unknown;
    else REQUIRE(got == truth(ref, id));
    ref.insert(id);
    REQUIRE(ids.ranges() <= kMax);
    const int64_t probe = static_cast<int64_t>(rng() % 120000);
    const Membership p = ids.contains(probe);
    if (p != Membership::Unknown) REQUIRE(p == truth(ref, probe));
  }
  CHECK_FALSE(ids.exact());
  // The newest ids stay exact: a merge takes the lowest ranges first.
  if (pattern == 0) {
    CHECK(ids.contains(3 * 19999 + 7) == Membership::Yes);
    CHECK(ids.contains(3 * 19999 + 8) == Membership::No);
    CHECK(ids.contains(7) == Membership::Unknown);
    CHECK(unknown == 0);  // ascending ids never fall in a merged range
  }
}

TEST_CASE("trace id set: ids at the ends of int64 join ranges without overflow", "[trace]") {
  // Found by the structured fuzz mutator: the id 2^63 - 1 overflowed a range's end.
  constexpr int64_t kMax = std::numeric_limits<int64_t>::max();
  TraceIdSet ids(2);
  CHECK(ids.insert(kMax) == Membership::No);
  CHECK(ids.insert(kMax) == Membership::Yes);
  CHECK(ids.insert(kMax - 1) == Membership::No);
  CHECK(ids.ranges() == 1);
  CHECK(ids.insert(0) == Membership::No);
  CHECK(ids.contains(kMax - 1) == Membership::Yes);
  CHECK(ids.contains(kMax - 2) == Membership::No);
  CHECK(ids.insert(5) == Membership::No);  // three ranges in a set of two: the lowest two merge
  CHECK(ids.contains(3) == Membership::Unknown);
  CHECK(ids.contains(kMax) == Membership::Yes);
}
