// The cycle-level model's outputs pinned to committed expected files
// (traces/bunny/cycle-expected/, README there): the stats of `vbsim replay
// --mode cycle` on the bundled trace and of the cycle-level replay of random
// bunny rays, for both presets with their memory hierarchy and with ideal
// memory and several methods, and the hits files' bytes. A change of the
// model's structure must leave every one of them byte for byte as it is; a
// change of its timing rules regenerates them on purpose:
//
//   VBSIM_WRITE_CYCLE_EXPECTED=1 build/vbsim_tests "[golden]"
//
// Compared: the JSON dumped with two-space indent, less the fields that are
// not results of the model: wall-clock time, paths, and the per-instance
// sections that later versions add (listed in strip_unpinned()).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/functional_bench.h"
#include "hw/cycle_replay.h"
#include "datapath/self_intersection_method.h"
#include "replay/replay_stats.h"
#include "run_vbsim.h"
#include "scene/bvh.h"
#include "scene/scene.h"

using namespace vbsim;
using vbsim::test::read_file;
using vbsim::test::run_vbsim;
using vbsim::test::scratch_dir;
using vbsim::test::source_dir;
using vbsim::test::write_file;

namespace {

namespace fs = std::filesystem;

fs::path expected_dir() { return fs::path(source_dir()) / "traces/bunny/cycle-expected"; }

bool writing() {
  const char* v = std::getenv("VBSIM_WRITE_CYCLE_EXPECTED");
  return v && std::string(v) == "1";
}

/// Removes what is not a result of the model (wall-clock figures, paths) and
/// sections that extend the stats beyond what the expected files pin.
void strip_unpinned(nlohmann::json& j) {
  if (j.contains("sim")) {
    j["sim"].erase("wall_s");
    j["sim"].erase("rays_per_s");
  }
  if (j.contains("config")) {
    j["config"].erase("trace");
    j["config"].erase("scene");
    j["config"].erase("bvh");  // the BVH build options, added later (their defaults build the pinned tree)
    // Configuration fields added after the files were pinned (their defaults are the pinned behaviour).
    if (j["config"].contains("hw")) {
      nlohmann::json& hw = j["config"]["hw"];
      hw["memory"].erase("tlm");
      hw["memory"].erase("at_lookahead_cycles");
      hw["memory"].erase("l2_lookups_in_time_order");
      hw["memory"].erase("dram_latency_per_byte");
      hw["memory"]["l1"].erase("ports");
      hw["memory"]["l1"].erase("port_cycles");
      hw["memory"]["l1"].erase("merge_misses");
      hw["memory"]["l2"].erase("merge_misses");
      for (const char* f : {"rays_per_cycle", "window", "dependencies", "missing_parents", "bundles", "bundle_cycles",
                            "bundle_max", "emission_width", "emission_depth"})
        hw["source"].erase(f);
      hw.erase("shader");
      hw.erase("controller");
      hw.erase("root_box_test");
      hw.erase("pop_culling");
      hw.erase("box_low");
      for (const char* unit : {"box", "triangle", "avoidance"}) hw[unit].erase("share");
      hw.erase("triangle_fetch");
      hw.erase("triangle_fetch_cycles");
      for (const char* f : {"warmup_rays", "warmup_cycles", "interval_cycles"}) hw["sim"].erase(f);
    }
  }
  for (const char* extra : {"provenance", "vbsim", "checks", "offset_fallbacks", "energy"}) j.erase(extra);
  if (j.contains("hw")) {
    j["hw"].erase("instances");
    j["hw"].erase("emission");
    j["hw"].erase("energy");
    j["hw"].erase("area");
    // Latency percentiles, miss latency per level, warm-up (docs/hw-model.md, "Statistics").
    for (const char* f : {"latency_distribution", "miss_latency", "warmup", "measured"}) j["hw"].erase(f);
  }
  // Counts added after the files were pinned: the per-ray result operations,
  // the emission operations by ray category, and the traversal stack's pushes
  // and pops (energy model, docs/energy.md).
  if (j.contains("config") && j["config"].contains("cost_ops")) {
    j["config"]["cost_ops"].erase("result");
    j["config"]["cost_ops"].erase("by_ray");
  }
  const auto strip_stack = [](nlohmann::json& t) {
    t.erase("stack_pushes");
    t.erase("stack_pops");
  };
  if (j.contains("traversal")) strip_stack(j["traversal"]);
  if (j.contains("by_kind"))
    for (nlohmann::json& k : j["by_kind"])
      if (k.contains("traversal")) strip_stack(k["traversal"]);
}

/// The SystemC run's duration (in whole picoseconds: the fields are converted
/// from SystemC time through seconds) in place of its start and end: each run
/// now has a simulation context of its own and starts at time 0, where earlier
/// versions let time grow across the runs of one process.
void as_duration(nlohmann::json& j) {
  if (!j.contains("hw") || !j["hw"].contains("systemc")) return;
  nlohmann::json& sc = j["hw"]["systemc"];
  sc["duration_ps"] = std::llround(sc["end_ps"].get<double>() - sc["start_ps"].get<double>());
  sc.erase("start_ps");
  sc.erase("end_ps");
}

/// 64-bit FNV-1a of `bytes`, in hex, with the length: an equality check of a
/// whole file in a line of JSON.
std::string digest(const std::string& bytes) {
  uint64_t h = 1469598103934665603ull;
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[40];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return std::string(buf) + ":" + std::to_string(bytes.size());
}

/// A hits file's rays: its first line, the provenance header that later
/// versions write, left out.
std::string without_hits_header(const std::string& text) {
  if (text.rfind(R"({"format":"vbsim-hits")", 0) != 0) return text;
  const size_t eol = text.find('\n');
  return eol == std::string::npos ? std::string() : text.substr(eol + 1);
}

/// Compares `got` with the expected file `name` (or writes it).
void check_expected(const std::string& name, const std::string& got_text) {
  const fs::path file = expected_dir() / name;
  if (writing()) {
    fs::create_directories(expected_dir());
    write_file(file, got_text);
    SUCCEED("wrote " << file);
    return;
  }
  REQUIRE(fs::exists(file));
  std::string want = read_file(file), got = got_text;
  if (name != "hits-digests.json") {  // stats: compared with the run's duration for its start and end
    nlohmann::json w = nlohmann::json::parse(want), g = nlohmann::json::parse(got);
    as_duration(w);
    as_duration(g);
    want = w.dump(2);
    got = g.dump(2);
  }
  const fs::path written = fs::temp_directory_path() / ("vbsim_cycle_expected_got_" + name);
  if (got != want) write_file(written, got);  // for a diff against the expected file
  INFO(name << " (what this run gave: " << written.string() << ")");
  CHECK(got == want);
}

struct Variant {
  std::string preset, memory, method;
  std::string name() const {
    std::string m = method;
    for (char& c : m)
      if (c == '+' || c == ':' || c == '=') c = '_';
    return preset + "-" + memory + "-" + m;
  }
};

std::vector<Variant> bunny_variants() {
  std::vector<Variant> out;
  for (const char* preset : {"small", "large"})
    for (const char* memory : {"hierarchy", "ideal"})
      for (const char* method : {"validity-bit", "tmin", "primid", "none", "offset-adaptive+primid"})
        out.push_back({preset, memory, method});
  // A policy with no epsilon test, the vote policy and a second tester, on the default preset.
  out.push_back({"small", "hierarchy", "sign-only"});
  out.push_back({"small", "hierarchy", "validity-bit:vb-policy=vote"});
  out.push_back({"small", "hierarchy", "validity-bit:tester=moller-trumbore"});
  return out;
}

/// `vbsim replay` arguments for a method entry METHOD[:KEY=VALUE...].
std::string method_args(const std::string& entry) {
  std::string args;
  size_t at = entry.find(':');
  args += " -m " + entry.substr(0, at);
  while (at != std::string::npos) {
    const size_t next = entry.find(':', at + 1);
    const std::string kv = entry.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1);
    const size_t eq = kv.find('=');
    args += " --" + kv.substr(0, eq) + " " + kv.substr(eq + 1);
    at = next;
  }
  return args;
}

}  // namespace

TEST_CASE("cycle-level stats and hits of the bundled trace match the committed expected files",
          "[cycle][system][golden]") {
  const fs::path dir = scratch_dir("cycle_golden");
  const fs::path ideal = dir / "ideal.json";
  write_file(ideal, R"({"hw": {"memory": {"ideal": true}}})");
  nlohmann::json hits_digests = nlohmann::json::object();
  for (const Variant& v : bunny_variants()) {
    const fs::path stats = dir / (v.name() + ".json"), hits = dir / (v.name() + ".hits.jsonl");
    std::string args = "replay " + source_dir() + "/traces/bunny/paths.jsonl --mode cycle --deps off --preset " + v.preset +
                       method_args(v.method) + " --stats " + stats.string() + " --hits " + hits.string() + " -q";
    if (v.memory == "ideal") args += " --config " + ideal.string();
    const auto r = run_vbsim(args);
    INFO(args << "\n" << r.output);
    REQUIRE(r.exit_code == 0);
    nlohmann::json j = nlohmann::json::parse(read_file(stats));
    strip_unpinned(j);
    check_expected(v.name() + ".json", j.dump(2) + "\n");
    hits_digests[v.name()] = digest(without_hits_header(read_file(hits)));
  }
  check_expected("hits-digests.json", hits_digests.dump(2) + "\n");
  fs::remove_all(dir);
}

TEST_CASE("cycle-level stats of random bunny rays match the committed expected files", "[cycle][system][golden]") {
  const Scene scene = load_scene(source_dir() + "/traces/bunny/bunny.obj");
  const Bvh bvh = build_bvh(scene);
  const std::vector<TraceRay> rays = bench_rays(scene, 20000, 1);
  for (const char* preset : {"small", "large"})
    for (const bool ideal : {false, true}) {
      hw::HwConfig cfg = hw::load_preset(preset, "test");
      cfg.memory.ideal = ideal;
      cfg.source.dependencies = false;  // camera rays: no parents either way
      cfg.source.window = 1u << 20;     // looking ahead as far as the model before the emission buffer
      ReplayOptions opt;
      std::string err;
      REQUIRE(parse_method("validity-bit", opt.method, err));
      size_t next = 0;
      const hw::RayFeed feed = [&](TraceRay& tr) {
        if (next == rays.size()) return false;
        tr = rays[next++];
        return true;
      };
      hw::CycleRunOptions options;
      options.track_parents = false;
      const hw::CycleRunResult run = hw::run_cycle_replay(feed, scene, bvh, opt, cfg, {}, options);
      nlohmann::json j = run.stats.to_json(replay_config_json(opt));
      j["hw"] = run.hw;
      strip_unpinned(j);
      check_expected(std::string("random-") + preset + (ideal ? "-ideal" : "-hierarchy") + ".json", j.dump(2) + "\n");
    }
}
