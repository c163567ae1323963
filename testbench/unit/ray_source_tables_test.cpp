// The ray source's two tables against plain standard-library models on random
// streams: IdPositionMap (open addressing, backward-shift deletion) against
// std::map, ReadyQueue (FIFO ring plus heap) against std::priority_queue.
#include <catch2/catch.hpp>

#include <map>
#include <queue>
#include <random>

#include "hw/source/id_position_map.h"
#include "hw/source/ready_queue.h"

using namespace vbsim::hw;

TEST_CASE("the id table finds what a std::map holds through inserts and erasures", "[hw][source]") {
  // Capacity 64: the first table holds it; 5000: the table doubles as ids arrive.
  for (const uint32_t capacity : {64u, 5000u}) {
    INFO("capacity " << capacity);
    std::mt19937_64 rng(11);
    const int64_t range = capacity < 100 ? 300 : 5 * int64_t{capacity};
    IdPositionMap table(capacity);
    std::map<int64_t, uint64_t> model;
    std::vector<std::pair<int64_t, uint64_t>> live;  // in insertion order
    for (uint64_t pos = 0; pos < 20000; ++pos) {
      if (live.size() == capacity) {  // the oldest leaves, as the source's history does
        table.erase(live.front().first, live.front().second);
        model.erase(live.front().first);
        live.erase(live.begin());
      }
      // Ids from a small range collide in the table; each id is live at most once.
      int64_t id;
      do id = static_cast<int64_t>(rng() % range) - 100;
      while (model.count(id));
      table.set(id, pos);
      model[id] = pos;
      live.push_back({id, pos});
      for (int k = 0; k < 4; ++k) {
        const int64_t probe = static_cast<int64_t>(rng() % range) - 100;
        uint64_t got = 0;
        const bool found = table.find(probe, got);
        REQUIRE(found == (model.count(probe) == 1));
        if (found) REQUIRE(got == model[probe]);
      }
    }
  }
}

TEST_CASE("the ready queue gives positions smallest first, like a priority queue", "[hw][source]") {
  std::mt19937_64 rng(5);
  ReadyQueue q(256);
  std::priority_queue<uint64_t, std::vector<uint64_t>, std::greater<uint64_t>> model;
  uint64_t next = 0;
  for (int step = 0; step < 50000; ++step) {
    if (model.size() < 200 && rng() % 3 != 0) {
      // Mostly increasing positions, now and then one behind.
      const uint64_t pos = rng() % 8 == 0 && next > 50 ? next - 1 - rng() % 50 : next++;
      q.push(pos);
      model.push(pos);
    } else if (!model.empty()) {
      REQUIRE(q.top() == model.top());
      q.pop();
      model.pop();
    }
    REQUIRE(q.empty() == model.empty());
  }
}
