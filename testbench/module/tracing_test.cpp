// Tracing per module instance: the VCD's values at cycle resolution and the
// timeline's named processes, threads and intervals, checked against the
// hand-computed run of one ray on the three-floor BVH (one core, one slot,
// ideal memory of 3 cycles; box 5, triangle 11):
//   dispatch 1, root box [1, 6); node 0: read [6, 9), boxes [9, 14);
//   node 1: read [14, 17), boxes [17, 22); leaf: read [22, 25), triangle [25, 36); done 36.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "../unit/three_floors.h"
#include "hw/cycle_replay.h"
#include "hw/observe/trace_scope.h"

using namespace vbsim;
using namespace vbsim::hw;
using namespace vbsim::hw::test;

namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("vbsim_tracing_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

CycleRunResult run_one_ray(const CycleRunOptions& options, uint32_t cores = 1) {
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);
  cfg.cores = cores;
  std::vector<TraceRay> rays;
  for (uint32_t c = 0; c < cores; ++c) rays.push_back(down_from(1 + c, 1.0f));
  const RayFeed feed = feed_of(rays);
  return run_cycle_replay(feed, f.scene, f.bvh, ReplayOptions{}, cfg, {}, options);
}

/// A VCD read back: for each signal (scope.path.name), its (cycle, value) changes.
std::map<std::string, std::vector<std::pair<uint64_t, uint64_t>>> read_vcd(const fs::path& file, uint64_t period_ps) {
  std::ifstream in(file);
  std::map<std::string, std::string> name_of;  // id -> full name
  std::vector<std::string> scope;
  std::map<std::string, std::vector<std::pair<uint64_t, uint64_t>>> out;
  std::string word;
  uint64_t now = 0;
  while (in >> word) {
    if (word == "$scope") {
      std::string kind, name;
      in >> kind >> name;
      scope.push_back(name);
    } else if (word == "$upscope") {
      scope.pop_back();
    } else if (word == "$var") {
      std::string type, width, id, name;
      in >> type >> width >> id >> name;
      std::string full;
      for (const std::string& s : scope) full += s + ".";
      name_of[id] = full + name;
    } else if (word[0] == '#') {
      now = std::stoull(word.substr(1)) / period_ps;
    } else if (word[0] == 'b') {
      std::string id;
      in >> id;
      out[name_of.at(id)].push_back({now, std::stoull(word.substr(1), nullptr, 2)});
    }
  }
  return out;
}

using Changes = std::vector<std::pair<uint64_t, uint64_t>>;

}  // namespace

TEST_CASE("the VCD shows each instance's values at the cycles they change", "[module][tracing]") {
  const fs::path dir = scratch("vcd");
  CycleRunOptions options;
  options.track_parents = false;
  options.vcd = {(dir / "run.vcd").string(), 0, 100, ""};
  const CycleRunResult r = run_one_ray(options);
  REQUIRE(r.counters.cycles == 36);
  const auto v = read_vcd(dir / "run.vcd", 2000);  // 500 MHz: 2000 ps a cycle
  CHECK(v.at("accelerator.core_0.box_unit.ops_in_flight") ==
        Changes{{0, 0}, {1, 1}, {6, 0}, {9, 1}, {14, 0}, {17, 1}, {22, 0}});
  CHECK(v.at("accelerator.core_0.triangle_tester.ops_in_flight") == Changes{{0, 0}, {25, 1}, {36, 0}});
  CHECK(v.at("accelerator.core_0.avoidance_unit.ops_in_flight") == Changes{{0, 0}});
  CHECK(v.at("accelerator.core_0.busy_slots") == Changes{{0, 0}, {1, 1}, {36, 0}});
  // Reads [6, 9), [14, 17), [22, 25).
  CHECK(v.at("accelerator.core_0.reads_in_flight") ==
        Changes{{0, 0}, {6, 1}, {9, 0}, {14, 1}, {17, 0}, {22, 1}, {25, 0}});
  CHECK(v.at("accelerator.rays_done") == Changes{{0, 0}, {36, 1}});
  CHECK(v.at("accelerator.ray_source.rays_emitted") == Changes{{0, 0}, {0, 1}});  // emission starts at 0
  CHECK(v.at("accelerator.ray_source.rays_waiting") == Changes{{0, 0}, {0, 1}, {1, 0}});  // dispatched at 1

  // A window that starts inside the run: the levels at its start, then its changes.
  options.vcd = {(dir / "late.vcd").string(), 10, 15, ""};
  run_one_ray(options);
  const auto late = read_vcd(dir / "late.vcd", 2000);
  CHECK(late.at("accelerator.core_0.box_unit.ops_in_flight") == Changes{{10, 1}, {14, 0}, {17, 1}, {22, 0}});
  CHECK(late.at("accelerator.core_0.busy_slots") == Changes{{10, 1}});
  fs::remove_all(dir);
}

TEST_CASE("the timeline names processes and threads by instance and shows unit and memory events",
          "[module][tracing]") {
  const fs::path dir = scratch("timeline");
  CycleRunOptions options;
  options.track_parents = false;
  options.timeline = {(dir / "t.json").string(), 0, 1000, ""};
  run_one_ray(options);
  const auto t = nlohmann::json::parse(std::ifstream(dir / "t.json"));
  std::map<int, std::string> process;
  std::map<std::pair<int, int>, std::string> thread;
  std::map<std::string, std::vector<std::pair<uint64_t, uint64_t>>> intervals;  // "thread/name" -> [start, end)
  for (const auto& e : t["traceEvents"]) {
    if (e["ph"] == "M" && e["name"] == "process_name") process[e["pid"]] = e["args"]["name"];
    if (e["ph"] == "M" && e["name"] == "thread_name") thread[{e["pid"], e["tid"]}] = e["args"]["name"];
  }
  for (const auto& e : t["traceEvents"]) {
    if (e["ph"] != "X") continue;
    const std::string key = process.at(e["pid"]) + "/" + thread.at({e["pid"], e["tid"]}) + "/" +
                            e["name"].get<std::string>();
    const uint64_t ts = e["ts"];
    intervals[key].push_back({ts, ts + e["dur"].get<uint64_t>()});
  }
  using Iv = std::vector<std::pair<uint64_t, uint64_t>>;
  CHECK(intervals["accelerator.core_0/slot 0/node"] == Iv{{6, 14}, {14, 22}});
  CHECK(intervals["accelerator.core_0/slot 0/leaf"] == Iv{{22, 36}});
  CHECK(intervals["accelerator.core_0/box_unit/box"] == Iv{{1, 6}, {9, 14}, {17, 22}});
  CHECK(intervals["accelerator.core_0/triangle_tester/triangle"] == Iv{{25, 36}});
  CHECK(intervals["accelerator.core_0/memory reads/node"] == Iv{{6, 9}, {14, 17}});
  CHECK(intervals["accelerator.core_0/memory reads/leaf"] == Iv{{22, 25}});

  // One instance only.
  options.timeline = {(dir / "core1.json").string(), 0, 1000, "accelerator.core_1"};
  run_one_ray(options, 2);
  const auto one = nlohmann::json::parse(std::ifstream(dir / "core1.json"));
  bool core1 = false, other = false;
  for (const auto& e : one["traceEvents"])
    if (e["ph"] == "M" && e["name"] == "process_name") {
      const std::string p = e["args"]["name"];
      (p == "accelerator.core_1" ? core1 : other) = true;
    }
  CHECK(core1);
  CHECK_FALSE(other);
  fs::remove_all(dir);
}

TEST_CASE("a trace scope names one instance exactly and not those that share its prefix", "[module][tracing]") {
  const fs::path dir = scratch("scope");
  CycleRunOptions options;
  options.track_parents = false;
  options.timeline = {(dir / "t.json").string(), 0, 1000, "accelerator.core_1"};
  options.vcd = {(dir / "v.vcd").string(), 0, 1000, "accelerator.core_1"};
  run_one_ray(options, 11);  // cores 0 to 10, one ray each
  std::set<std::string> processes;
  const auto timeline = nlohmann::json::parse(std::ifstream(dir / "t.json"));
  for (const auto& e : timeline["traceEvents"])
    if (e["ph"] == "M" && e["name"] == "process_name") processes.insert(e["args"]["name"].get<std::string>());
  CHECK(processes == std::set<std::string>{"accelerator.core_1"});
  std::set<std::string> signals;
  for (const auto& [name, changes] : read_vcd(dir / "v.vcd", 2000)) signals.insert(name);
  CHECK(signals.count("accelerator.core_1.busy_slots") == 1);
  CHECK(signals.count("accelerator.core_1.box_unit.ops_in_flight") == 1);
  for (const std::string& n : signals) CHECK(n.rfind("accelerator.core_1.", 0) == 0);

  // A pattern: every core's box unit.
  options.timeline.path.clear();
  options.vcd.scope = "accelerator.core_*.box_unit";
  run_one_ray(options, 11);
  signals.clear();
  for (const auto& [name, changes] : read_vcd(dir / "v.vcd", 2000)) signals.insert(name);
  CHECK(signals.size() == 11);
  CHECK(signals.count("accelerator.core_10.box_unit.ops_in_flight") == 1);

  // A scope that names nothing: an error naming it, and no file.
  fs::remove(dir / "v.vcd");
  options.vcd.scope = "accelerator.core_11";
  CHECK_THROWS_AS(run_one_ray(options, 11), TraceScopeError);
  CHECK_THROWS_WITH(run_one_ray(options, 11), Catch::Contains("'accelerator.core_11'") &&
                                                  Catch::Contains("accelerator.core_10"));
  CHECK_FALSE(fs::exists(dir / "v.vcd"));
  fs::remove_all(dir);
}

TEST_CASE("the VCD has the L2, DRAM and ray source and ends with the run", "[module][tracing]") {
  const fs::path dir = scratch("vcd_memory");
  CycleRunOptions options;
  options.track_parents = false;
  options.vcd = {(dir / "run.vcd").string(), 0, 1000000, ""};
  const ThreeFloors f;
  HwConfig cfg = one_slot(3, 5, 11, 7);
  cfg.memory = MemoryConfig{};  // the cache hierarchy and the built-in DRAM
  const std::vector<TraceRay> rays = {down_from(1, 1.0f), down_from(2, 1.0f)};
  const CycleRunResult r = run_cycle_replay(feed_of(rays), f.scene, f.bvh, ReplayOptions{}, cfg, {}, options);
  const uint64_t period = 2000, end = r.counters.cycles;
  const auto v = read_vcd(dir / "run.vcd", period);
  const auto last = [&](const std::string& name) { return v.at(name).back().second; };
  // The DRAM delivered every byte the statistics count; nothing is left in flight.
  CHECK(last("accelerator.dram.bytes") == r.hw["memory"]["port"]["dram"]["bytes"]);
  CHECK(last("accelerator.dram.bytes") > 0);
  CHECK(last("accelerator.dram.requests_in_flight") == 0);
  CHECK(last("accelerator.l2_cache.misses_in_flight") == 0);
  uint64_t l2_peak = 0;
  for (const auto& [cycle, value] : v.at("accelerator.l2_cache.misses_in_flight")) l2_peak = std::max(l2_peak, value);
  CHECK(l2_peak >= 1);
  CHECK(last("accelerator.ray_source.rays_emitted") == 2);
  CHECK(last("accelerator.ray_source.rays_waiting") == 0);
  CHECK(v.at("accelerator.ray_source.rays_waiting").size() >= 2);  // the second ray waited for the slot
  // The file ends after the run's last cycle, not at the window's end.
  std::ifstream in(dir / "run.vcd");
  std::string line, final_time;
  while (std::getline(in, line))
    if (!line.empty() && line[0] == '#') final_time = line;
  CHECK(final_time == "#" + std::to_string((end + 1) * period));
  fs::remove_all(dir);
}

TEST_CASE("the hw statistics hold every instance's declared statistics by hierarchical name", "[module][tracing]") {
  CycleRunOptions options;
  options.track_parents = false;
  const CycleRunResult r = run_one_ray(options, 2);
  const auto& inst = r.hw["instances"];
  CHECK(inst["accelerator.core_0.box_unit"]["ops"] == 3);  // the root box and two nodes
  CHECK(inst["accelerator.core_1.triangle_tester"]["ops"] == 1);
  CHECK(inst["accelerator.core_0"]["node_fetches"] == 2);
  CHECK(inst["accelerator.ray_source"]["rays"] == 2);
  CHECK(inst["accelerator.result_sink"]["rays"] == 2);
  CHECK(inst["accelerator.memory"]["reads"] == 6);  // the ideal memory: 3 reads a ray
  // The chip-wide totals are the sums of the instances'.
  CHECK(r.hw["units"]["box"]["ops"] ==
        inst["accelerator.core_0.box_unit"]["ops"].get<uint64_t>() +
            inst["accelerator.core_1.box_unit"]["ops"].get<uint64_t>());
}
