// UnitPipelines against hand-computed reservations and against a plain model of
// its rule (every issue cycle of every pipeline kept in a set; an operation takes
// the earliest cycle >= its ready cycle at which some pipeline has its whole
// issue interval free, the lowest such pipeline).
#include <catch2/catch.hpp>

#include <random>
#include <set>
#include <vector>

#include "hw/unit_pipelines.h"

using namespace vbsim::hw;

namespace {

class PlainPipelines {
 public:
  PlainPipelines(uint32_t count, uint32_t interval) : taken_(count), interval_(interval) {}
  uint64_t issue(uint64_t ready) {
    for (uint64_t c = ready;; ++c)
      for (size_t p = 0; p < taken_.size(); ++p) {
        bool free = true;
        for (uint64_t k = 0; k < interval_ && free; ++k) free = taken_[p].count(c + k) == 0;
        if (!free) continue;
        for (uint64_t k = 0; k < interval_; ++k) taken_[p].insert(c + k);
        return c;
      }
  }

 private:
  std::vector<std::set<uint64_t>> taken_;
  uint64_t interval_;
};

}  // namespace

TEST_CASE("a pipeline issues a later-ready operation after and an earlier-ready one before a reservation", "[pipelines]") {
  UnitCounters totals;
  UnitPipelines box(UnitConfig{1, 8, 1}, totals);
  // At cycle 10 a node from DRAM is ready at 200; at cycle 12 one from the L1 at 14.
  CHECK(box.issue(200, 10) == 200);
  CHECK(box.issue(14, 12) == 14);  // not held back behind 200
  CHECK(box.issue(14, 13) == 15);  // 14 is taken: the next cycle
  CHECK(box.issue(200, 20) == 201);  // same ready cycle: the earlier request keeps 200
  CHECK(box.issue(199, 30) == 199);
  CHECK(box.issue(199, 31) == 202);  // 199, 200, 201 taken
  CHECK(totals.ops == 6);
  CHECK(totals.wait_cycles == 0 + 0 + 1 + 1 + 0 + 3);
  CHECK(box.latency() == 8);
}

TEST_CASE("pipelines with an issue interval of 3 fill gaps only where 3 cycles are free", "[pipelines]") {
  UnitCounters totals;
  UnitPipelines tri(UnitConfig{1, 20, 3}, totals);
  CHECK(tri.issue(10, 0) == 10);  // holds 10, 11, 12
  CHECK(tri.issue(15, 0) == 15);  // holds 15, 16, 17
  CHECK(tri.issue(8, 0) == 18);   // 8..10 overlaps 10; 13..15 overlaps 15: after 17
  CHECK(tri.issue(5, 1) == 5);    // 5, 6, 7 are free
  UnitPipelines two(UnitConfig{2, 4, 2}, totals);
  CHECK(two.issue(0, 0) == 0);  // pipeline 0: 0, 1
  CHECK(two.issue(0, 0) == 0);  // pipeline 1: 0, 1
  CHECK(two.issue(1, 0) == 2);  // both busy at 1
}

TEST_CASE("pipelines match the plain reservation model on random streams", "[pipelines]") {
  struct Shape { uint32_t count, interval; };
  for (const Shape shape : {Shape{1, 1}, Shape{1, 3}, Shape{2, 1}, Shape{3, 2}, Shape{4, 1}}) {
    UnitCounters totals;
    UnitPipelines pipes(UnitConfig{shape.count, 5, shape.interval}, totals);
    PlainPipelines plain(shape.count, shape.interval);
    std::mt19937_64 rng(shape.count * 100 + shape.interval);
    // Requests at about 90% of the pipelines' capacity (count / interval per cycle).
    std::exponential_distribution<double> gap(shape.count / (1.1 * shape.interval));
    std::uniform_int_distribution<int> near_far(0, 9), near(0, 30), far(100, 5000);
    double clock = 0;
    uint64_t now = 0, waited = 0, backfilled = 0, last = 0;
    for (int i = 0; i < 20000; ++i) {
      clock += gap(rng);
      now = static_cast<uint64_t>(clock);
      // Mostly soon, now and then far ahead (beyond the first window: it must grow).
      const uint64_t ready = now + static_cast<uint64_t>(near_far(rng) ? near(rng) : far(rng));
      const uint64_t got = pipes.issue(ready, now), want = plain.issue(ready);
      INFO("pipelines " << shape.count << " interval " << shape.interval << " request " << i);
      REQUIRE(got == want);
      waited += got > ready;
      backfilled += got < last;
      last = got;
    }
    CHECK(totals.ops == 20000);
    INFO("waited " << waited << " backfilled " << backfilled);
    CHECK(waited > 500);      // the stream exercised busy cycles
    CHECK(backfilled > 500);  // and operations that went before earlier reservations
  }
}
