// ParentOrderCheck and its RecentIdWindow: a child before its parent is found
// in bounded memory, at the child while ids ascend, at the parent otherwise.
#include <catch2/catch.hpp>

#include <algorithm>
#include <deque>
#include <random>

#include "trace/parent_order_check.h"

using namespace vbsim;
using Kind = ParentOrderProblem::Kind;

TEST_CASE("recent id window: lookups agree with the last W ids, ascending or not", "[trace][checks]") {
  std::mt19937_64 rng(13);
  for (std::size_t capacity : {1u, 3u, 64u}) {
    RecentIdWindow window(capacity);
    std::deque<int64_t> reference;  // the last `capacity` ids, oldest first
    std::vector<int64_t> pushed;
    int64_t next = 0;
    for (int i = 0; i < 2000; ++i) {
      // Ascending with gaps for 1000 ids, then shuffled ids (never repeated).
      const int64_t id = i < 1000 ? (next += 1 + static_cast<int64_t>(rng() % 3)) : 100000 + (i * 7919) % 1000;
      const std::size_t slot = window.push(id);
      CHECK(slot < capacity);
      reference.push_back(id);
      pushed.push_back(id);
      if (reference.size() > capacity) reference.pop_front();
      for (int probe = 0; probe < 4; ++probe) {
        const int64_t q = pushed[rng() % pushed.size()] + static_cast<int64_t>(rng() % 2);
        const bool present = std::find(reference.begin(), reference.end(), q) != reference.end();
        CHECK((window.find(q) >= 0) == present);
      }
      CHECK(window.find(id) == static_cast<int64_t>(slot));
    }
    CHECK_FALSE(window.ascending());
    CHECK(window.size() == capacity);
  }
}

TEST_CASE("parent order: ascending ids decide child-before-parent at the child", "[trace][checks]") {
  ParentOrderCheck check(8);
  CHECK_FALSE(check.add(0, -1, 2).problem);
  const ParentOrderCheck::Step child = check.add(1, 0, 3);
  CHECK_FALSE(child.problem);
  CHECK(child.parent_slot == static_cast<int64_t>(check.window().find(0)));
  CHECK_FALSE(check.add(4, 2, 4).problem);  // parent 2 is not in the trace: allowed
  const ParentOrderCheck::Step later = check.add(5, 9, 5);
  REQUIRE(later.problem);
  CHECK(later.problem.kind == Kind::ParentLater);
  CHECK(later.problem.child_id == 5);
  CHECK(later.problem.parent_id == 9);
  CHECK(later.problem.child_position == 5);
  CHECK_THAT(later.problem.message("line"), Catch::Contains("child before parent") && Catch::Contains("9 > 5"));
  const ParentOrderCheck::Step own = check.add(6, 6, 6);
  REQUIRE(own.problem);
  CHECK(own.problem.kind == Kind::OwnParent);
}

TEST_CASE("parent order: without ascending ids the error comes at the parent and names the child", "[trace][checks]") {
  ParentOrderCheck check(8);
  CHECK_FALSE(check.add(10, -1, 2).problem);
  CHECK_FALSE(check.add(3, 7, 3).problem);   // ids stop ascending; parent 7 not seen yet
  CHECK_FALSE(check.add(4, 10, 4).problem);  // parent 10 is in the window
  const ParentOrderCheck::Step parent = check.add(7, -1, 5);
  REQUIRE(parent.problem);
  CHECK(parent.problem.kind == Kind::ParentArrived);
  CHECK(parent.problem.child_id == 3);
  CHECK(parent.problem.child_position == 3);
  CHECK(parent.problem.parent_id == 7);
  CHECK_THAT(parent.problem.message("line"), Catch::Contains("ray 7 is the parent of ray 3 (line 3)"));
  CHECK(check.unchecked() == 0);
}

TEST_CASE("parent order: the window and the waiting list stay bounded", "[trace][checks]") {
  SECTION("dense ascending ids: parents within the window are found, older ones are not") {
    ParentOrderCheck check(4);
    for (int64_t id = 0; id < 100; ++id) {
      const int64_t parent = id >= 5 ? id - (id % 2 == 0 ? 1 : 5) : -1;
      const ParentOrderCheck::Step s = check.add(id, parent, id);
      CHECK_FALSE(s.problem);
      if (parent >= 0) CHECK((s.parent_slot >= 0) == (id - parent <= 4));
    }
  }
  SECTION("children of missing parents beyond the capacity are counted as unchecked") {
    ParentOrderCheck check(2);
    CHECK_FALSE(check.add(100, -1, 0).problem);
    for (int64_t k = 0; k < 5; ++k) CHECK_FALSE(check.add(50 - k, 1000 + k, k + 1).problem);
    CHECK(check.unchecked() == 3);  // room for two waiting children
    // The parent of the latest child still arrives in time to be caught...
    CHECK(check.add(1004, -1, 9).problem.kind == Kind::ParentArrived);
    // ...the parent of the first one no longer can be.
    CHECK_FALSE(check.add(1000, -1, 10).problem);
  }
}
