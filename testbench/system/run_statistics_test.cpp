// The statistics an architect reads beside the totals, on the bundled trace:
// exact latency percentiles (overall and per ray kind) against the per-ray
// times sorted here, histogram buckets that hold every ray, interval
// statistics whose rows sum to the run's totals, and a warm-up that takes out
// exactly the rays (and cycles) it excludes.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

#include "hw/cycle_replay.h"
#include "replay/replay_run.h"
#include "trace/trace_file.h"
#include "trace/trace_source.h"

using namespace vbsim;

namespace {

namespace fs = std::filesystem;

struct FinishedRay {
  std::string kind;
  uint64_t start = 0, finish = 0;
  uint64_t latency() const { return finish - start; }
};

struct Run {
  hw::CycleRunResult result;
  std::map<int64_t, FinishedRay> rays;  // by ray id
};

/// The bundled trace on the small preset (caches), dependencies off, with `cfg_edit` applied.
Run run_bundled(const hw::CycleRunOptions& base, void (*cfg_edit)(hw::HwConfig&) = nullptr) {
  const std::string path = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";
  ReplayOptions opt;
  std::string err;
  REQUIRE(parse_method("validity-bit", opt.method, err));
  auto src = open_trace(path);
  const SceneAndBvh sb = load_trace_scene(src->header());
  src->set_triangle_count(sb.scene.size());
  hw::HwConfig cfg = hw::resolve_hw_config("", "small");
  cfg.source.dependencies = false;
  if (cfg_edit) cfg_edit(cfg);
  Run run;
  hw::CycleRunOptions options = base;
  options.ray_times = [&run](const hw::RayTimes& t) {
    run.rays[t.id].start = t.started;
    run.rays[t.id].finish = t.finished;
  };
  const hw::RayResultSink sink = [&run](const TraceRay& tr, const RayOutcome&, uint64_t, uint64_t) {
    run.rays[tr.id].kind = ray_kind_name(tr.kind);
  };
  run.result = hw::run_cycle_replay([&](TraceRay& r) { return src->next(r); }, sb.scene, sb.bvh, opt, cfg, sink, options);
  return run;
}

/// The nearest-rank percentile of `v` (sorted here): the ceil(p/100 n)-th smallest.
uint64_t nearest_rank(std::vector<uint64_t> v, double p) {
  std::sort(v.begin(), v.end());
  const size_t rank = std::max<size_t>(1, static_cast<size_t>(std::ceil(p / 100.0 * static_cast<double>(v.size()))));
  return v[rank - 1];
}

void check_summary(const nlohmann::json& got, const std::vector<uint64_t>& latencies) {
  REQUIRE(got["rays"] == latencies.size());
  CHECK(got["min"] == *std::min_element(latencies.begin(), latencies.end()));
  CHECK(got["max"] == *std::max_element(latencies.begin(), latencies.end()));
  for (const double p : {50.0, 90.0, 95.0, 99.0}) {
    INFO("p" << p);
    CHECK(got["p" + std::to_string(static_cast<int>(p))] == nearest_rank(latencies, p));
  }
  uint64_t sum = 0;
  for (const uint64_t l : latencies) sum += l;
  CHECK(got["mean"].get<double>() == Approx(static_cast<double>(sum) / static_cast<double>(latencies.size())));
}

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("vbsim_run_statistics_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

}  // namespace

TEST_CASE("latency percentiles overall and per kind are the per-ray latencies' nearest ranks", "[system][cycle][stats]") {
  const Run run = run_bundled({});
  const nlohmann::json& d = run.result.hw["latency_distribution"];
  REQUIRE(run.rays.size() == 1008);
  std::vector<uint64_t> all;
  std::map<std::string, std::vector<uint64_t>> by_kind;
  for (const auto& [id, r] : run.rays) {
    all.push_back(r.latency());
    by_kind[r.kind].push_back(r.latency());
  }
  check_summary(d["overall"], all);
  CHECK(d["by_kind"].size() == by_kind.size());
  for (const auto& [kind, v] : by_kind) {
    INFO(kind);
    check_summary(d["by_kind"][kind], v);
  }
  // The log2 buckets hold every ray, the longest in the last bucket.
  uint64_t in_buckets = 0;
  for (const auto& b : d["log2_histogram"]) {
    uint64_t n = 0;
    for (const uint64_t l : all) n += l >= b["from"].get<uint64_t>() && l < b["to"].get<uint64_t>();
    CHECK(b["rays"] == n);
    in_buckets += b["rays"].get<uint64_t>();
  }
  CHECK(in_buckets == 1008);
  const auto& last = d["log2_histogram"].back();
  CHECK(last["rays"].get<uint64_t>() > 0);
  CHECK(d["overall"]["max"].get<uint64_t>() < last["to"].get<uint64_t>());
}

TEST_CASE("interval statistics sum to the run's totals", "[system][cycle][stats]") {
  const fs::path dir = scratch("intervals");
  hw::CycleRunOptions options;
  options.interval_stats = (dir / "intervals.jsonl").string();
  const Run run = run_bundled(options, [](hw::HwConfig& c) { c.interval_cycles = 1500; });
  const nlohmann::json& hw = run.result.hw;
  std::ifstream in(dir / "intervals.jsonl");
  std::string line;
  uint64_t rows = 0, rays = 0, l1_hits = 0, l1_misses = 0, l2_hits = 0, l2_misses = 0, dram_bytes = 0, box = 0,
           triangle = 0, expected_start = 0;
  std::map<uint64_t, uint64_t> finished_in;  // interval start -> rays, from the per-ray times
  for (const auto& [id, r] : run.rays) ++finished_in[r.finish - r.finish % 1500];
  while (std::getline(in, line)) {
    const auto j = nlohmann::json::parse(line);
    INFO(line);
    CHECK(j["start"] == expected_start);
    expected_start = j["end"];
    CHECK(j["cycles"] == j["end"].get<uint64_t>() - j["start"].get<uint64_t>());
    CHECK(j["rays"] == finished_in[j["start"]]);  // each ray in the interval it finished in
    CHECK(j["rays_per_cycle"].get<double>() == Approx(j["rays"].get<double>() / j["cycles"].get<double>()));
    rays += j["rays"].get<uint64_t>();
    l1_hits += j["l1"]["hits"].get<uint64_t>();
    l1_misses += j["l1"]["misses"].get<uint64_t>();
    l2_hits += j["l2"]["hits"].get<uint64_t>();
    l2_misses += j["l2"]["misses"].get<uint64_t>();
    dram_bytes += j["dram"]["bytes"].get<uint64_t>();
    box += j["units"]["box"]["ops"].get<uint64_t>();
    triangle += j["units"]["triangle"]["ops"].get<uint64_t>();
    CHECK(j["units"]["box"]["busy"].get<double>() >= 0);
    ++rows;
  }
  const uint64_t cycles = hw["cycles"];
  CHECK(rows == cycles / 1500 + 1);  // full intervals, then the last one to the cycle after the last ray
  CHECK(expected_start == cycles + 1);
  CHECK(rays == 1008);
  CHECK(l1_hits == hw["memory"]["port"]["l1"]["hits"]);
  CHECK(l1_misses == hw["memory"]["port"]["l1"]["misses"]);
  CHECK(l2_hits == hw["memory"]["port"]["l2"]["hits"]);
  CHECK(l2_misses == hw["memory"]["port"]["l2"]["misses"]);
  CHECK(dram_bytes == hw["memory"]["port"]["dram"]["bytes"]);
  CHECK(box == hw["units"]["box"]["ops"]);
  CHECK(triangle == hw["units"]["triangle"]["ops"]);
  // Statistics never move a cycle.
  const Run plain = run_bundled({});
  CHECK(plain.result.hw["cycles"] == hw["cycles"]);
  CHECK(plain.result.hw["units"] == hw["units"]);
  fs::remove_all(dir);
}

TEST_CASE("a warm-up excludes exactly the rays and cycles before its end", "[system][cycle][stats]") {
  const Run plain = run_bundled({});
  // A warm-up that excludes no ray (cycle 1: no ray finishes at cycle 0)
  // measures what the run without one does.
  const Run one_cycle = run_bundled({}, [](hw::HwConfig& c) { c.warmup_cycles = 1; });
  const nlohmann::json& m = one_cycle.result.hw["measured"];
  CHECK(one_cycle.result.hw["warmup"]["excluded_rays"] == 0);
  CHECK(m["rays"] == 1008);
  CHECK(m["cycles"] == plain.result.hw["cycles"]);
  CHECK(m["latency_distribution"] == plain.result.hw["latency_distribution"]);
  CHECK(m["miss_latency"] == plain.result.hw["miss_latency"]);
  CHECK(m["units"]["box"]["ops"] == plain.result.hw["units"]["box"]["ops"]);
  CHECK(m["l1"]["misses"] == plain.result.hw["memory"]["port"]["l1"]["misses"]);

  // 300 rays: measured from the cycle after the 300th finished.
  const Run warm = run_bundled({}, [](hw::HwConfig& c) { c.warmup_rays = 300; });
  const nlohmann::json& hw = warm.result.hw;
  REQUIRE(hw.contains("measured"));
  std::vector<uint64_t> finishes;
  for (const auto& [id, r] : warm.rays) finishes.push_back(r.finish);
  std::sort(finishes.begin(), finishes.end());
  const uint64_t from = finishes[299] + 1;
  CHECK(hw["warmup"]["by"] == "rays");
  CHECK(hw["warmup"]["measured_from_cycle"] == from);
  std::vector<uint64_t> after;
  for (const auto& [id, r] : warm.rays)
    if (r.finish >= from) after.push_back(r.latency());
  CHECK(hw["warmup"]["excluded_rays"] == 1008 - after.size());
  CHECK(hw["measured"]["rays"] == after.size());
  CHECK(hw["measured"]["cycles"] == hw["cycles"].get<uint64_t>() + 1 - from);
  check_summary(hw["measured"]["latency_distribution"]["overall"], after);
  CHECK(hw["cycles"] == plain.result.hw["cycles"]);  // the run itself is the same

  // By cycle: the rays finished at or after it.
  const Run at_cycle = run_bundled({}, [](hw::HwConfig& c) { c.warmup_cycles = 2000; });
  uint64_t later = 0;
  for (const auto& [id, r] : at_cycle.rays) later += r.finish >= 2000;
  CHECK(at_cycle.result.hw["warmup"]["measured_from_cycle"] == 2000);
  CHECK(at_cycle.result.hw["measured"]["rays"] == later);
  CHECK(at_cycle.result.hw["warmup"]["excluded_rays"] == 1008 - later);

  // A warm-up past the run's end leaves nothing to measure: an error.
  CHECK_THROWS_WITH(run_bundled({}, [](hw::HwConfig& c) { c.warmup_rays = 1008; }),
                    Catch::Contains("excludes every ray"));
}

TEST_CASE("the miss latency per cache level is the reads' wait when every read misses", "[system][cycle][stats]") {
  // One ray on the bundled scene with cold caches: its reads each miss in the
  // L1 and the L2 (checked), so a read's wait is the L1 miss latency, and the
  // L2's is that less the L1's lookup.
  const std::string path = std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/paths.jsonl";
  auto src = open_trace(path);
  const SceneAndBvh sb = load_trace_scene(src->header());
  src->set_triangle_count(sb.scene.size());
  TraceRay first;
  REQUIRE(src->next(first));
  hw::HwConfig cfg = hw::resolve_hw_config("", "small");
  cfg.cores = 1;
  cfg.slots_per_core = 1;
  bool fed = false;
  const hw::CycleRunResult r = hw::run_cycle_replay(
      [&](TraceRay& tr) { return fed ? false : (tr = first, fed = true); }, sb.scene, sb.bvh, ReplayOptions{}, cfg, {},
      hw::CycleRunOptions{});
  const nlohmann::json& port = r.hw["memory"]["port"];
  const uint64_t reads = r.counters.node_fetches + r.counters.leaf_fetches;
  INFO(r.hw.dump(1));
  REQUIRE(r.counters.refill_reads == 0);
  REQUIRE(port["l1"]["hits"] == 0);
  REQUIRE(port["l1"]["merges"] == 0);
  REQUIRE(port["l2"]["hits"] == 0);
  REQUIRE(port["l1"]["misses"] == reads);  // one line a read
  const double wait = static_cast<double>(r.counters.memory_wait_cycles) / static_cast<double>(reads);
  CHECK(r.hw["miss_latency"]["l1"]["mean_cycles"].get<double>() == Approx(wait));
  CHECK(r.hw["miss_latency"]["l2"]["mean_cycles"].get<double>() == Approx(wait - cfg.memory.l1.hit_latency));
}
