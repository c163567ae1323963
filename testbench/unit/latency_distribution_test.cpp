// LatencyDistribution: nearest-rank percentiles and log2 buckets, by hand.
#include <catch2/catch.hpp>

#include "hw/observe/latency_distribution.h"

using namespace vbsim::hw;

TEST_CASE("latency percentiles are nearest ranks of the latencies", "[unit][stats]") {
  LatencyDistribution d;
  CHECK(d.percentile(50) == 0);
  // 10 rays: 1..10 cycles, given out of order.
  for (const uint64_t l : {7, 3, 10, 1, 9, 2, 8, 5, 4, 6}) d.add(l);
  CHECK(d.rays() == 10);
  CHECK(d.min() == 1);
  CHECK(d.max() == 10);
  CHECK(d.mean() == Approx(5.5));
  CHECK(d.percentile(50) == 5);   // rank ceil(5) = 5
  CHECK(d.percentile(90) == 9);   // rank 9
  CHECK(d.percentile(95) == 10);  // rank ceil(9.5) = 10
  CHECK(d.percentile(99) == 10);
  CHECK(d.percentile(100) == 10);
  CHECK(d.percentile(10) == 1);
  CHECK(d.percentile(11) == 2);  // rank ceil(1.1) = 2

  // Buckets [0,1) [1,2) [2,4) [4,8) [8,16): every ray in one, none open-ended.
  const auto h = d.log2_histogram_json();
  REQUIRE(h.size() == 5);
  CHECK(h[0]["rays"] == 0);
  CHECK(h[1]["rays"] == 1);
  CHECK(h[2]["rays"] == 2);
  CHECK(h[3]["rays"] == 4);
  CHECK(h[4]["from"] == 8);
  CHECK(h[4]["to"] == 16);
  CHECK(h[4]["rays"] == 3);

  // A snapshot taken away leaves the rays after it.
  const LatencyDistribution before = d;
  d.add(1000);
  d.add(2);
  d.subtract(before);
  CHECK(d.rays() == 2);
  CHECK(d.min() == 2);
  CHECK(d.max() == 1000);
  CHECK(d.percentile(50) == 2);
  CHECK(d.log2_histogram_json().back()["to"] == 1024);
}
