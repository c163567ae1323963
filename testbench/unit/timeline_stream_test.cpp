// TimelineRecorder: intervals go to the file as they are added (bounded
// memory), each on the lowest lane free at its start; the file is named only
// by finish(), and a recorder dropped unfinished leaves nothing.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "hw/observe/timeline_recorder.h"

using namespace vbsim::hw;
namespace fs = std::filesystem;

namespace {
fs::path scratch() {
  const fs::path p = fs::temp_directory_path() / ("vbsim_timeline_stream_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}
/// The regular files in `dir`.
size_t other_files(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file();
  return n;
}
}  // namespace

TEST_CASE("timeline intervals take the lowest free lane of their track", "[unit][tracing]") {
  const fs::path dir = scratch();
  TimelineRecorder t((dir / "t.json").string(), 0, 1000, TraceScope());
  const uint32_t unit = t.track("accelerator.core_0", "box_unit");
  // A pipeline with three operations in flight, [0,8) [1,9) [2,10): three lanes; then
  // [8,16) reuses lane 0 and [9,12) lane 1; [3,5), added late, finds every lane
  // busy or reserved past 3 (their last intervals end at 16, 12, 10): lane 3.
  t.add(unit, "box", 0, 8, 1);
  t.add(unit, "box", 1, 9, 2);
  t.add(unit, "box", 2, 10, 3);
  t.add(unit, "box", 8, 16, 4);
  t.add(unit, "box", 9, 12, 5);
  t.add(unit, "box", 3, 5, 6);
  t.add(unit, "box", 2000, 2001, 7);  // outside the window
  CHECK(t.events() == 6);
  CHECK(t.lanes() == 4);
  t.finish();
  const auto j = nlohmann::json::parse(std::ifstream(dir / "t.json"));
  std::map<int, std::string> names;
  std::map<int64_t, int> lane_of;  // ray -> tid
  for (const auto& e : j["traceEvents"]) {
    if (e["ph"] == "M" && e["name"] == "thread_name") names[e["tid"]] = e["args"]["name"];
    if (e["ph"] == "X") lane_of[e["args"]["ray"]] = e["tid"];
  }
  CHECK(names.at(lane_of[1]) == "box_unit");
  CHECK(names.at(lane_of[2]) == "box_unit #1");
  CHECK(names.at(lane_of[3]) == "box_unit #2");
  CHECK(lane_of[4] == lane_of[1]);
  CHECK(lane_of[5] == lane_of[2]);
  CHECK(names.at(lane_of[6]) == "box_unit #3");
  fs::remove_all(dir);
}

TEST_CASE("the timeline is streamed to its temporary and named only when finished", "[unit][tracing]") {
  const fs::path dir = scratch();
  {
    TimelineRecorder t((dir / "t.json").string(), 0, ~uint64_t{0} / 2, TraceScope());
    const uint32_t slot = t.track("accelerator.core_0", "slot 0");
    for (uint64_t i = 0; i < 200000; ++i) t.add(slot, "node", 2 * i, 2 * i + 1, static_cast<int64_t>(i));
    // Written as it went (the temporary holds most of it), no file under the name yet.
    CHECK_FALSE(fs::exists(dir / "t.json"));
    REQUIRE(other_files(dir) == 1);
    CHECK(fs::file_size(fs::directory_iterator(dir)->path()) > 200000 * 50);
    CHECK(t.lanes() == 1);
  }  // dropped unfinished (a run that threw): nothing left
  CHECK(other_files(dir) == 0);
  fs::remove_all(dir);
}
