// ParentRayStore against a plain reference model (a deque of the ids in the
// window and a map of every id ever added), over hand-made and random
// sequences: what is held, what was dropped, memory bounded by the window.
#include <catch2/catch.hpp>

#include <deque>
#include <map>
#include <random>
#include <set>

#include "trace/parent_ray_store.h"

using namespace vbsim;

namespace {

Vec3f origin_of(int64_t id) { return {static_cast<float>(id), 1.0f, 2.0f}; }

/// What the contract says the store holds: the last `window` distinct ids added.
struct ReferenceWindow {
  int64_t window;
  std::deque<int64_t> order;            // ids held, oldest first
  std::map<int64_t, ParentRay> held;
  std::set<int64_t> ever;

  void add(int64_t id, ParentRay r) {
    ever.insert(id);
    if (held.count(id)) {
      held[id] = r;
      return;
    }
    if (static_cast<int64_t>(order.size()) == window) {
      held.erase(order.front());
      order.pop_front();
    }
    order.push_back(id);
    held[id] = r;
  }
};

}  // namespace

TEST_CASE("parent store: held rays are found, unknown ids are not", "[parents]") {
  ParentRayStore store(4);
  CHECK(store.lookup(0) == nullptr);
  CHECK(store.lookup(-1) == nullptr);
  store.add(10, {1, 2, 3}, {0, 0, 1});
  store.add(11, {4, 5, 6}, {0, 1, 0});
  const ParentRay* p = store.lookup(10);
  REQUIRE(p != nullptr);
  CHECK(p->o == Vec3f{1, 2, 3});
  CHECK(p->d == Vec3f{0, 0, 1});
  CHECK(store.lookup(12) == nullptr);  // not added (yet): a parent not in the trace
  store.add(10, {7, 7, 7}, {1, 0, 0});  // an id held again: replaced in place
  CHECK(store.lookup(10)->o == Vec3f{7, 7, 7});
  CHECK(store.size() == 2);
}

TEST_CASE("parent store: a dropped parent is an error naming it and the window", "[parents]") {
  ParentRayStore store(3);
  for (int64_t id = 0; id < 5; ++id) store.add(id, origin_of(id), {0, 0, 1});
  CHECK(store.size() == 3);
  CHECK(store.lookup(2) != nullptr);
  CHECK(store.lookup(4)->o.x == 4.0f);
  CHECK_THROWS_AS(store.lookup(1), ParentWindowError);
  CHECK_THROWS_WITH(store.lookup(0), Catch::Contains("parent 0") && Catch::Contains("3 rays") &&
                                         Catch::Contains("--parent-window"));
  CHECK(store.lookup(5) == nullptr);  // never added: no error
}

TEST_CASE("parent store: window limits", "[parents]") {
  CHECK_THROWS_AS(ParentRayStore(0), std::invalid_argument);
  CHECK_THROWS_AS(ParentRayStore(ParentRayStore::kMaxWindow + 1), std::invalid_argument);
  ParentRayStore one(1);
  one.add(5, {}, {1, 0, 0});
  one.add(6, {}, {1, 0, 0});
  CHECK_THROWS_AS(one.lookup(5), ParentWindowError);
  CHECK(one.lookup(6) != nullptr);
}

TEST_CASE("parent store: random sequences agree with the reference model", "[parents]") {
  const int64_t window = GENERATE(1, 2, 7, 64, 1000);
  const int ids_kind = GENERATE(0, 1, 2);  // dense in order, shuffled blocks, sparse 64-bit
  std::mt19937_64 rng(static_cast<uint64_t>(window * 31 + ids_kind));
  ParentRayStore store(window);
  ReferenceWindow ref{window, {}, {}, {}};
  int64_t next = 0;
  for (int step = 0; step < 20000; ++step) {
    int64_t id = next++;
    if (ids_kind == 1) id = (id / 8) * 8 + (7 - id % 8);  // out of order within blocks of 8
    if (ids_kind == 2) id = static_cast<int64_t>(rng() >> 1);
    if (step % 10 == 9 && !ref.order.empty()) id = ref.order[rng() % ref.order.size()];  // re-add a held id
    const ParentRay r{origin_of(step), {0, 0, static_cast<float>(step + 1)}};
    store.add(id, r.o, r.d);
    ref.add(id, r);
    REQUIRE(store.size() == static_cast<int64_t>(ref.order.size()));
    // Probe a held id, a dropped one and a fresh one.
    const int64_t held = ref.order[rng() % ref.order.size()];
    const ParentRay* p = store.lookup(held);
    REQUIRE(p != nullptr);
    REQUIRE(p->d.z == ref.held[held].d.z);
    const int64_t probe = ids_kind == 2 ? static_cast<int64_t>(rng() >> 1) : static_cast<int64_t>(rng() % (next + 8));
    if (ref.held.count(probe)) REQUIRE(store.lookup(probe)->o.x == ref.held[probe].o.x);
    else if (ref.ever.count(probe)) REQUIRE_THROWS_AS(store.lookup(probe), ParentWindowError);
    else if (store.dropped_ids_exact()) REQUIRE(store.lookup(probe) == nullptr);
    else {
      // Ids in more ranges than the record keeps: a fresh id is either known
      // fresh or refused as unknown, never taken for a dropped one.
      std::string refusal;
      const ParentRay* found = nullptr;
      try {
        found = store.lookup(probe);
      } catch (const ParentWindowError& e) {
        refusal = e.what();
      }
      REQUIRE(found == nullptr);
      if (!refusal.empty()) REQUIRE_THAT(refusal, Catch::Contains("no longer known"));
    }
  }
}

TEST_CASE("parent store: ids in order from an outlying first id keep the record exact", "[parents]") {
  // One swapped id at the start made the old record of dropped ids grow with the trace.
  ParentRayStore store(4);
  store.add(1000000000, {}, {1, 0, 0});
  for (int64_t id = 0; id < 300000; ++id) store.add(id, {}, {1, 0, 0});
  CHECK(store.dropped_ids_exact());
  CHECK_THROWS_WITH(store.lookup(1000000000), Catch::Contains("more than 4 rays before"));
  CHECK_THROWS_AS(store.lookup(12345), ParentWindowError);
  CHECK(store.lookup(300000) == nullptr);  // never added
  CHECK(store.lookup(299999) != nullptr);
}
