// EventWheel against hand-computed orders and against a plain model of its rule
// (every pending event kept in an ordered set by (cycle, scheduling order)),
// including events scheduled for the cycle being handed out, events far beyond
// the window (the overflow heap) and takes bounded by a limit.
#include <catch2/catch.hpp>

#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "hw/scheduler/event_wheel.h"

using namespace vbsim::hw;

namespace {

struct Taken {
  uint64_t at;
  uint32_t id;
  bool operator==(const Taken& o) const { return at == o.at && id == o.id; }
};

/// Every event taken before `limit`.
std::vector<Taken> take_all(EventWheel& w, uint64_t limit = ~uint64_t{0}) {
  std::vector<Taken> out;
  uint64_t at = 0;
  uint32_t id = 0;
  while (w.take(limit, at, id)) out.push_back({at, id});
  return out;
}

class PlainEvents {
 public:
  void schedule(uint64_t at, uint32_t id) { pending_.insert({at, order_++, id}); }
  bool take(uint64_t limit, uint64_t& at, uint32_t& id) {
    if (pending_.empty() || std::get<0>(*pending_.begin()) >= limit) return false;
    at = std::get<0>(*pending_.begin());
    id = std::get<2>(*pending_.begin());
    pending_.erase(pending_.begin());
    return true;
  }
  bool empty() const { return pending_.empty(); }
  uint64_t next_cycle() const { return std::get<0>(*pending_.begin()); }

 private:
  std::set<std::tuple<uint64_t, uint64_t, uint32_t>> pending_;
  uint64_t order_ = 0;
};

}  // namespace

TEST_CASE("events of one cycle come out in the order they were scheduled, not by id", "[wheel]") {
  EventWheel w(8, 4);  // a 16-cycle window
  w.schedule(5, 6);
  w.schedule(3, 2);
  w.schedule(5, 1);
  w.schedule(5, 4);
  w.schedule(40, 3);  // beyond the window: the overflow heap
  w.schedule(40, 0);
  CHECK(w.next_cycle() == 3);
  uint64_t at = 0;
  uint32_t id = 0;
  REQUIRE(w.take(100, at, id));
  CHECK((at == 3 && id == 2));
  REQUIRE(w.take(100, at, id));
  CHECK((at == 5 && id == 6));
  CHECK(w.peek_next() == 1);
  w.schedule(5, 6);  // scheduled while cycle 5 is handed out: after the ones already there
  w.schedule(40, 7);  // still beyond the window from cycle 5: after 3 and 0
  CHECK(take_all(w, 6) == std::vector<Taken>{{5, 1}, {5, 4}, {5, 6}});
  CHECK(w.next_cycle() == 40);
  w.schedule(30, 5);  // in the window now
  CHECK(take_all(w) == std::vector<Taken>{{30, 5}, {40, 3}, {40, 0}, {40, 7}});
  CHECK(w.empty());
}

TEST_CASE("an event scheduled for the current cycle after its last one was taken is still handed out", "[wheel]") {
  EventWheel w(4, 3);
  w.schedule(2, 3);
  uint64_t at = 0;
  uint32_t id = 0;
  REQUIRE(w.take(10, at, id));
  CHECK(w.peek_next() == EventWheel::kNone);  // nothing at cycle 2 or 3
  w.schedule(2, 3);  // the same id again, same cycle
  w.schedule(2, 1);
  w.schedule(9, 0);
  CHECK(take_all(w) == std::vector<Taken>{{2, 3}, {2, 1}, {9, 0}});
}

TEST_CASE("the wheel's hint names the next cycle's first event when the current cycle is used up", "[wheel]") {
  EventWheel w(6, 4);
  w.schedule(4, 5);
  w.schedule(5, 2);
  w.schedule(5, 0);
  uint64_t at = 0;
  uint32_t id = 0;
  REQUIRE(w.take(10, at, id));
  CHECK((at == 4 && id == 5));
  CHECK(w.peek_next() == 2);  // cycle 4 is used up; cycle 5 starts with 2
  REQUIRE(w.take(10, at, id));
  CHECK(w.peek_next() == 0);
  REQUIRE(w.take(10, at, id));
  CHECK(w.peek_next() == EventWheel::kNone);
}

TEST_CASE("the wheel hands out events in the plain model's order on random streams", "[wheel]") {
  std::mt19937_64 rng(20261130);
  for (const uint32_t window_log2 : {2u, 4u, 10u}) {
    const uint32_t ids = 40;
    EventWheel w(ids, window_log2);
    PlainEvents plain;
    std::vector<bool> busy(ids, false);
    uint64_t now = 0, limit = 0;
    size_t taken = 0;
    for (int round = 0; round < 20000; ++round) {
      // Schedule some idle ids at now + a delay: mostly near, sometimes at now,
      // sometimes far beyond the window.
      for (uint32_t id = 0; id < ids; ++id) {
        if (busy[id] || rng() % 3 != 0) continue;
        const uint64_t kind = rng() % 10;
        const uint64_t delay = kind == 0 ? 0 : kind < 8 ? rng() % 12 : 50 + rng() % 3000;
        w.schedule(now + delay, id);
        plain.schedule(now + delay, id);
        busy[id] = true;
      }
      REQUIRE(w.empty() == plain.empty());
      if (plain.empty()) continue;
      REQUIRE(w.next_cycle() == plain.next_cycle());
      limit += rng() % 6;
      uint64_t at = 0, plain_at = 0;
      uint32_t id = 0, plain_id = 0;
      const int burst = 1 + static_cast<int>(rng() % 4);
      for (int k = 0; k < burst; ++k) {
        const bool got = w.take(limit, at, id);
        REQUIRE(got == plain.take(limit, plain_at, plain_id));
        if (!got) break;
        REQUIRE(at == plain_at);
        REQUIRE(id == plain_id);
        busy[id] = false;
        now = at;
        ++taken;
      }
    }
    CHECK(taken > 5000);
  }
}
