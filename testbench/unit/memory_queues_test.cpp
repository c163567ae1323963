// The memory model's bookkeeping structures against plain versions of their
// rules: the calendar queue (TimedQueue) against a binary heap of (cycle, push
// order); the waiters of pending lines (LineWaiters) against one flat list
// scanned per fill; the DRAM channel's request slots against a scan for the
// slot that frees first; the MSHRs' free cycles with unknown fills
// (CacheLevel::hold_mshr, resolve) against a plain list. Random streams, each
// answer compared, and hand-computed cases.
#include <catch2/catch.hpp>

#include <algorithm>
#include <functional>
#include <queue>
#include <random>
#include <tuple>
#include <vector>

#include "hw/memory/cache_level.h"
#include "hw/memory/dram_channel.h"
#include "hw/memory/line_waiters.h"
#include "hw/memory/timed_queue.h"

using namespace vbsim::hw;

namespace {

using Entry = std::tuple<uint64_t, uint64_t, uint64_t>;  // cycle, push order, payload

struct PlainQueue {
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
  uint64_t order = 0;
  void push(uint64_t cycle, uint64_t payload) { heap.push({cycle, order++, payload}); }
  uint64_t earliest() const { return heap.empty() ? kPendingCycle : std::get<0>(heap.top()); }
};

/// The flat list LineWaiters replaced: every fill scans every waiter.
struct PlainWaiters {
  struct W {
    uint64_t line;
    uint32_t who;
    uint64_t t;
  };
  std::vector<W> list;
  void add(uint64_t line, uint32_t who, uint64_t t) { list.push_back({line, who, t}); }
  std::vector<W> take(uint64_t line, bool all) {
    std::vector<W> mine, kept;
    size_t first = list.size();
    if (!all)
      for (size_t i = 0; i < list.size(); ++i)
        if (list[i].line == line && (first == list.size() || list[i].t < list[first].t)) first = i;
    for (size_t i = 0; i < list.size(); ++i) (all ? list[i].line == line : i == first) ? mine.push_back(list[i]) : kept.push_back(list[i]);
    list = kept;
    return mine;
  }
};

}  // namespace

TEST_CASE("TimedQueue hands entries out by cycle, then in the order they came", "[memory][queue]") {
  TimedQueue<uint64_t> q(4);  // a 16-cycle window
  CHECK(q.earliest() == kPendingCycle);
  q.push(100, 1);  // beyond the window: waits in the heap
  q.push(5, 2);
  q.push(5, 3);
  q.push(3, 4);
  q.push(100, 5);
  q.push(20, 6);  // beyond the window [0, 16)
  CHECK(q.earliest() == 3);
  uint64_t cycle = 0, payload = 0;
  CHECK_FALSE(q.pop_due(2, cycle, payload));
  std::vector<std::pair<uint64_t, uint64_t>> got;
  while (q.pop_due(50, cycle, payload)) got.push_back({cycle, payload});
  CHECK(got == std::vector<std::pair<uint64_t, uint64_t>>{{3, 4}, {5, 2}, {5, 3}, {20, 6}});
  q.push(100, 7);  // now in the window: after the two that came first, from the heap
  q.push(60, 8);
  got.clear();
  while (q.pop_due(1000, cycle, payload)) got.push_back({cycle, payload});
  CHECK(got == std::vector<std::pair<uint64_t, uint64_t>>{{60, 8}, {100, 1}, {100, 5}, {100, 7}});
  CHECK(q.empty());
}

TEST_CASE("TimedQueue matches a heap of (cycle, push order) on random streams", "[memory][queue]") {
  for (const uint32_t window_log2 : {2u, 6u, 10u}) {
    TimedQueue<uint64_t> q(window_log2);
    PlainQueue plain;
    std::mt19937_64 rng(window_log2);
    std::uniform_int_distribution<int> kind(0, 9), burst(0, 6);
    std::uniform_int_distribution<uint64_t> near(0, 40), far(500, 5000), back(0, 30);
    uint64_t now = 0, popped = 0;
    for (int i = 0; i < 20000; ++i) {
      for (int n = burst(rng); n > 0; --n) {
        const int k = kind(rng);
        // Mostly ahead of now, some far ahead, some at or before it.
        const uint64_t cycle = k < 7 ? now + near(rng) : k < 9 ? now + far(rng) : now - std::min(now, back(rng));
        q.push(cycle, i * 8 + n);
        plain.push(cycle, i * 8 + n);
      }
      INFO("window 2^" << window_log2 << " step " << i);
      REQUIRE(q.earliest() == plain.earliest());
      now += near(rng) / 4;
      uint64_t cycle, payload;
      while (q.pop_due(now, cycle, payload)) {
        REQUIRE_FALSE(plain.heap.empty());
        REQUIRE(cycle == std::get<0>(plain.heap.top()));
        REQUIRE(payload == std::get<2>(plain.heap.top()));
        plain.heap.pop();
        ++popped;
      }
      REQUIRE(plain.earliest() > now);
      REQUIRE(q.size() == plain.heap.size());
    }
    CHECK(popped > 20000);
  }
}

TEST_CASE("LineWaiters answer what a flat list of waiters answers, nested fills included", "[memory][queue]") {
  for (const bool merge : {true, false}) {
    CacheConfig config{4 * 64, 4, 64, 3, 4};
    config.merge_misses = merge;
    CacheLevel level(config), plain_level(config);
    LineWaiters waiters;
    PlainWaiters plain;
    std::mt19937_64 rng(merge ? 7 : 8);
    std::uniform_int_distribution<uint64_t> line_of(0, 40), dt(0, 30);
    std::uniform_int_distribution<uint32_t> who_of(0, 31);
    std::uniform_int_distribution<int> coin(0, 3);
    uint64_t t = 0, answered = 0, hits = 0;
    for (int i = 0; i < 20000; ++i) {
      t += dt(rng) / 8;
      const uint64_t line = line_of(rng);
      if (coin(rng) != 0) {
        const uint32_t who = who_of(rng);
        const uint64_t at = t + dt(rng);  // requests may be stamped ahead of now
        waiters.add(line, who, at);
        plain.add(line, who, at);
        continue;
      }
      const uint64_t fill = t + dt(rng);
      std::vector<std::pair<uint32_t, uint64_t>> got, want;
      // An answer adds a waiter for another line now and then, and fills one (nested).
      const uint64_t nested_line = (line + 1) % 41;
      std::vector<PlainWaiters::W> nested_want;
      waiters.fill(line, fill, level, [&](uint32_t who, uint64_t ready) {
        got.push_back({who, ready});
        if (who % 5 == 0) waiters.add(nested_line, who, ready);
        if (who % 7 == 0) waiters.fill(nested_line, ready + 1, level, [&](uint32_t w, uint64_t r) { got.push_back({w + 100, r}); });
      });
      for (const PlainWaiters::W& w : plain.take(line, merge)) {
        const bool hit = merge && w.t >= fill;
        if (hit) plain_level.recount_merge_as_hit(), ++hits;
        const uint64_t ready = hit ? w.t + config.hit_latency : fill;
        want.push_back({w.who, ready});
        if (w.who % 5 == 0) plain.add(nested_line, w.who, ready);
        if (w.who % 7 == 0)
          for (const PlainWaiters::W& n : plain.take(nested_line, merge)) {
            const bool nested_hit = merge && n.t >= ready + 1;
            if (nested_hit) plain_level.recount_merge_as_hit(), ++hits;
            want.push_back({n.who + 100, nested_hit ? n.t + config.hit_latency : ready + 1});
          }
      }
      INFO("merge " << merge << " step " << i);
      REQUIRE(got == want);
      REQUIRE(waiters.size() == plain.list.size());
      answered += got.size();
    }
    CHECK(level.counters().hits == plain_level.counters().hits);
    CHECK(answered > 5000);
    if (merge) CHECK(hits > 100);
  }
}

TEST_CASE("LineWaiters: merged waiters in arrival order, hits after the fill, one waiter a fill without merging",
          "[memory][queue]") {
  CacheConfig config{4 * 64, 4, 64, 3, 4};
  CacheLevel merging(config);
  LineWaiters w;
  w.add(9, 1, 10);
  w.add(4, 2, 11);
  w.add(9, 3, 30);  // after the fill at 25: a hit, ready at 33
  w.add(9, 4, 12);
  std::vector<std::pair<uint32_t, uint64_t>> got;
  w.fill(9, 25, merging, [&](uint32_t who, uint64_t ready) { got.push_back({who, ready}); });
  CHECK(got == std::vector<std::pair<uint32_t, uint64_t>>{{1, 25}, {3, 33}, {4, 25}});
  CHECK(w.size() == 1);
  config.merge_misses = false;
  CacheLevel own(config);
  w.add(4, 5, 9);  // line 4: asked at 11 (slot 2), then at 9 (slot 5): 5 asked first
  got.clear();
  w.fill(4, 40, own, [&](uint32_t who, uint64_t ready) { got.push_back({who, ready}); });
  CHECK(got == std::vector<std::pair<uint32_t, uint64_t>>{{5, 40}});
  w.fill(4, 41, own, [&](uint32_t who, uint64_t ready) { got.push_back({who, ready}); });
  CHECK(got == std::vector<std::pair<uint32_t, uint64_t>>{{5, 40}, {2, 41}});
  CHECK(w.size() == 0);
}

TEST_CASE("DRAM channel request slots: the slot that frees first, as a scan of every slot finds it",
          "[memory][queue]") {
  for (const uint32_t slots : {1u, 3u, 8u, 32u}) {
    DramChannel channel(120, 16.0, 64, slots);
    // The plain rules of dram_channel.h with a scan for the earliest free slot.
    std::vector<uint64_t> free(slots, 0);
    uint64_t channel_free = 0;
    const uint64_t per_cycle = channel.ticks_per_cycle(), per_transfer = channel.ticks_per_transfer();
    std::mt19937_64 rng(slots);
    std::uniform_int_distribution<uint64_t> gap(0, 12);
    uint64_t t = 0, waited = 0;
    for (int i = 0; i < 20000; ++i) {
      t += gap(rng) / 4;
      auto slot = std::min_element(free.begin(), free.end());
      const uint64_t start = std::max(*slot, t);
      const uint64_t start_ticks = start * per_cycle;
      channel_free = std::max(channel_free, start_ticks) + per_transfer;
      const uint64_t queued = (channel_free + per_cycle - 1) / per_cycle -
                              (start_ticks + per_transfer + per_cycle - 1) / per_cycle;
      const uint64_t want = start + 120 + queued;
      *slot = want;
      waited += start > t;
      INFO("slots " << slots << " read " << i);
      REQUIRE(channel.read_line(t) == want);
    }
    CHECK(waited > 100);
  }
}

TEST_CASE("MSHRs held until unknown fills: resolve gives the first of them its cycle", "[memory][queue]") {
  CacheLevel level(CacheConfig{4 * 64, 4, 64, 2, 5});
  std::vector<uint64_t> plain(5, 0);  // every MSHR's free cycle
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> coin(0, 2);
  std::uniform_int_distribution<uint64_t> dt(1, 60);
  uint64_t t = 0, resolved = 0;
  for (int i = 0; i < 20000; ++i) {
    t += dt(rng) / 10;
    const uint64_t front = *std::min_element(plain.begin(), plain.end());
    REQUIRE(level.mshr_free_cycle() == front);
    const bool pending = std::count(plain.begin(), plain.end(), kPendingCycle) != 0;
    if (pending && (coin(rng) == 0 || front == kPendingCycle)) {
      const uint64_t fill = t + dt(rng);
      level.resolve(1000 + i, fill);  // a line not in the array: only the MSHR takes the cycle
      *std::find(plain.begin(), plain.end(), kPendingCycle) = fill;
      ++resolved;
      continue;
    }
    const uint64_t fill = coin(rng) == 0 ? kPendingCycle : std::max(front, t) + dt(rng);
    level.hold_mshr(fill);
    *std::min_element(plain.begin(), plain.end()) = fill;
  }
  CHECK(resolved > 1000);
}
