// TraceIdSet: exact membership whatever the order ids come in; consecutive
// ids from any first id form one run.
#include <catch2/catch.hpp>

#include <random>
#include <set>

#include "trace/trace_validation.h"

using namespace vbsim;

TEST_CASE("trace id set: duplicates are found in any order, from any first id", "[trace]") {
  const int64_t first = GENERATE(0, 1, 1000000007);
  const int order = GENERATE(0, 1, 2);
  std::mt19937_64 rng(static_cast<uint64_t>(first + order));
  TraceIdSet ids;
  std::set<int64_t> ref;
  for (int i = 0; i < 5000; ++i) {
    int64_t id = first + i;
    if (order == 1) id = first + (i ^ 5);            // swapped neighbours
    if (order == 2) id = first + static_cast<int64_t>(rng() % 3000);  // repeats
    REQUIRE(ids.insert(id) == ref.insert(id).second);
    const int64_t probe = first + static_cast<int64_t>(rng() % 6000) - 10;
    REQUIRE(ids.contains(probe) == (ref.count(probe) == 1));
  }
}
