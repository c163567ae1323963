// The timeline puts every interval on a lane of its track so that no two
// slices of one thread overlap (Perfetto shows overlapping slices of a thread
// wrongly), on the default run and on the large preset with the bundled trace,
// and keeps every interval the run had (none dropped to make room).
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

struct Slice {
  uint64_t start, end;
  std::string name;
};

/// Per (pid, tid): the slices; checks that none overlaps another of its thread.
void check_no_overlap(const nlohmann::json& t, size_t& slices, size_t& threads, std::map<std::string, size_t>& by_name) {
  std::map<std::pair<int, int>, std::vector<Slice>> tracks;
  std::map<std::pair<int, int>, std::string> thread_names;
  for (const auto& e : t["traceEvents"]) {
    if (e["ph"] == "M" && e["name"] == "thread_name") thread_names[{e["pid"], e["tid"]}] = e["args"]["name"];
    if (e["ph"] != "X") continue;
    const uint64_t ts = e["ts"], dur = e["dur"];
    tracks[{e["pid"], e["tid"]}].push_back({ts, ts + dur, e["name"]});
    ++by_name[e["name"]];
    ++slices;
  }
  threads = tracks.size();
  size_t overlaps = 0;
  for (auto& [key, v] : tracks) {
    CHECK(thread_names.count(key) == 1);  // every thread named
    std::sort(v.begin(), v.end(), [](const Slice& a, const Slice& b) { return a.start < b.start; });
    for (size_t i = 1; i < v.size(); ++i)
      if (v[i].start < v[i - 1].end) {
        if (overlaps++ < 5)
          FAIL_CHECK(thread_names[key] << ": " << v[i - 1].name << " [" << v[i - 1].start << ", " << v[i - 1].end
                                       << ") overlaps " << v[i].name << " [" << v[i].start << ", " << v[i].end << ")");
      }
  }
  CHECK(overlaps == 0);
}

}  // namespace

TEST_CASE("no two timeline slices of one thread overlap", "[system][cycle][tracing]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto dir = scratch_dir("timeline_lanes");
  for (const std::string preset : {"small", "large"}) {
    INFO(preset);
    const RunResult r = run_vbsim("replay " + trace + " --mode cycle -q --preset " + preset + " --timeline " +
                                  (dir / "t.json").string() + " --timeline-cycles 100000000 --stats " +
                                  (dir / "s.json").string());
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const auto t = nlohmann::json::parse(read_file(dir / "t.json"));
    const auto s = nlohmann::json::parse(read_file(dir / "s.json"));
    size_t slices = 0, threads = 0;
    std::map<std::string, size_t> by_name;
    check_no_overlap(t, slices, threads, by_name);
    // Every operation of the whole run is there: the window covers it.
    CHECK(by_name["box"] == s["hw"]["units"]["box"]["ops"]);
    CHECK(by_name["triangle"] == s["hw"]["units"]["triangle"]["ops"]);
    CHECK(by_name["dram read"] == s["hw"]["memory"]["port"]["dram"]["reads"]);
    CHECK(threads > 4 * s["config"]["hw"]["cores"].get<size_t>());  // lanes beside the slots' threads
  }
  std::filesystem::remove_all(dir);
}
