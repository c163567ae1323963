// The progress line: hand-computed percentages, rates and times left.
#include <catch2/catch.hpp>

#include <cstdio>

#include "progress/progress_meter.h"

namespace vbsim {
namespace {

TEST_CASE("progress text: percentage, rate and time left", "[progress]") {
  // 250 of 1000 rays in 5 s: 50 rays/s, 750 left = 15 s.
  CHECK(progress_text("replay", 250, 1000, "rays", 5.0) == "replay   25.0%  250/1000 rays  50 rays/s  ETA 0:15");
  // 1 of 3 in 1 s: 2 left at 1/s = 2 s; nothing done: no ETA; all done: no ETA.
  CHECK(progress_text("x", 1, 3, "points", 1.0) == "x   33.3%  1/3 points  1 points/s  ETA 0:02");
  CHECK(progress_text("x", 0, 3, "points", 1.0) == "x    0.0%  0/3 points  0 points/s");
  CHECK(progress_text("x", 3, 3, "points", 1.0) == "x  100.0%  3/3 points  3 points/s");
  // Unknown total: count and rate only.
  CHECK(progress_text("oracle", 500, 0, "rays", 2.0) == "oracle  500 rays  250 rays/s");
}

TEST_CASE("clock text: m:ss below an hour, h:mm:ss from there, rounded up", "[progress]") {
  CHECK(clock_text(0) == "0:00");
  CHECK(clock_text(0.2) == "0:01");
  CHECK(clock_text(59.5) == "1:00");
  CHECK(clock_text(3599) == "59:59");
  CHECK(clock_text(3600) == "1:00:00");
  CHECK(clock_text(3 * 3600 + 62) == "3:01:02");
  CHECK(clock_text(-4) == "0:00");
}

TEST_CASE("a meter without a terminal writes nothing", "[progress]") {
  ProgressMeter meter("replay", 10, "rays", nullptr);
  CHECK(!meter.shown());
  meter.update(5);
  meter.finish();
  std::FILE* sink = std::tmpfile();
  {
    ProgressMeter shown("replay", 10, "rays", sink);
    CHECK(shown.shown());
    shown.add(3);  // within the first 200 ms: not drawn yet
  }                // the destructor clears nothing that was never drawn
  CHECK(std::ftell(sink) == 0);
  std::fclose(sink);
}

}  // namespace
}  // namespace vbsim
