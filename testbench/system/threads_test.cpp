// --threads: functional replay, oracle and check give byte-identical outputs
// (statistics less their wall-clock fields, hits files, the oracle's trace,
// check's report) and the same errors on 1, 2, 3 and 7 threads, on the bundled
// trace and on traces longer than one block; 0 or a negative count is refused.
#include <catch2/catch.hpp>

#include <functional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

const int kThreadCounts[] = {1, 2, 3, 7};

/// The JSON text of `path` without the fields that measure wall-clock time.
std::string without_clock(const std::filesystem::path& path) {
  nlohmann::json j = nlohmann::json::parse(read_file(path));
  const std::function<void(nlohmann::json&)> strip = [&](nlohmann::json& v) {
    if (v.is_object()) {
      for (const char* key : {"wall_s", "rays_per_s"}) v.erase(key);
      for (auto& [key, value] : v.items()) strip(value);
    } else if (v.is_array()) {
      for (auto& e : v) strip(e);
    }
  };
  strip(j);
  return j.dump(1);
}

/// A path-traced trace of about 15,000 rays over the bunny (children naming
/// their parents, expect filled in): longer than a block of every command.
std::string generated_trace(const std::filesystem::path& dir) {
  static std::string path;
  if (path.empty()) {
    const auto out = dir / "gen";
    const RunResult r = run_vbsim("gen paths --rays 3000 --seed 7 -q -o " + out.string());
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    for (const auto& e : std::filesystem::directory_iterator(out))
      if (e.path().extension() == ".jsonl") path = e.path().string();
    REQUIRE(!path.empty());
  }
  return path;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// `trace` with problems far apart, beyond the first blocks: a malformed line,
/// a field out of range, a duplicate id, rays without expect, comment and
/// blank lines (which move the line numbers), a child before its parent.
std::string damaged_trace(const std::string& trace, const std::filesystem::path& out) {
  std::vector<std::string> lines = lines_of(read_file(trace));
  REQUIRE(lines.size() > 12000);
  lines[4500] = "{\"id\":";
  lines[5000] = "# a comment\n\n" + lines[5000];
  lines[6100] = lines[6099];  // a duplicate id
  for (int i = 7000; i < 7040; ++i) {
    const std::size_t expect = lines[i].find(",\"expect\"");
    if (expect != std::string::npos) lines[i] = lines[i].substr(0, expect) + "}";
  }
  lines[9000] = "{\"id\":99999999,\"parent\":99999998,\"kind\":\"diffuse\",\"o\":[0,0,5],\"d\":[0,0,-1],"
                "\"parent_prim\":3,\"expect\":{\"prim\":-1}}\n"
                "{\"id\":99999998,\"o\":[0,0,5],\"d\":[0,0,-1],\"expect\":{\"prim\":-1}}";
  lines[11000] = "{\"id\":1,\"o\":[0,0,5],\"d\":[0,0,0]}";
  std::string text;
  for (const std::string& l : lines) text += l + "\n";
  write_file(out, text);
  return out.string();
}

}  // namespace

TEST_CASE("replay, oracle and check give byte-identical outputs on 1, 2, 3 and 7 threads", "[system][threads]") {
  const auto dir = scratch_dir("threads_outputs");
  const std::string bunny = source_dir() + "/traces/bunny/paths.jsonl";
  for (const std::string& trace : {bunny, generated_trace(dir)}) {
    INFO(trace);
    std::string stats[4], hits[4], oracle[4], check[4];
    for (int k = 0; k < 4; ++k) {
      INFO("threads " << kThreadCounts[k]);
      const std::string threads = " --threads " + std::to_string(kThreadCounts[k]);
      // The same outputs every time: their provenance names them.
      const auto s = dir / "s.json", h = dir / "h.jsonl", o = dir / "o.jsonl";
      RunResult r = run_vbsim("replay " + trace + " -q --method validity-bit --hitpoint barycentric --stats " +
                              s.string() + " --hits " + h.string() + threads);
      REQUIRE(r.exit_code == 0);
      stats[k] = without_clock(s);
      hits[k] = read_file(h);
      r = run_vbsim("oracle " + trace + " -q -o " + o.string() + threads);
      REQUIRE(r.exit_code == 0);
      oracle[k] = read_file(o);
      r = run_vbsim_raw("check " + trace + threads);
      REQUIRE(r.exit_code == 0);
      check[k] = r.output;
    }
    CHECK(hits[0].size() > 1008 * 30);
    CHECK(stats[0].find("\"provenance\"") != std::string::npos);
    CHECK(check[0].find("0 errors") != std::string::npos);
    for (int k = 1; k < 4; ++k) {
      INFO("threads " << kThreadCounts[k]);
      CHECK(stats[k] == stats[0]);
      CHECK(hits[k] == hits[0]);
      CHECK(oracle[k] == oracle[0]);
      CHECK(check[k] == check[0]);
    }
  }
}

TEST_CASE("a damaged trace gives the same report and errors on any number of threads", "[system][threads]") {
  const auto dir = scratch_dir("threads_errors");
  // Beside the generated trace, so that its header's relative scene path names the same file.
  const std::filesystem::path generated = generated_trace(dir);
  const std::string trace = damaged_trace(generated.string(), generated.parent_path() / "damaged.jsonl");
  std::string check[4], replay[4], oracle[4], window[4];
  for (int k = 0; k < 4; ++k) {
    const std::string threads = " --threads " + std::to_string(kThreadCounts[k]);
    RunResult r = run_vbsim_raw("check " + trace + threads);
    CHECK(r.exit_code == 1);
    check[k] = r.output;
    r = run_vbsim("replay " + trace + " -q --method tmin" + threads);
    CHECK(r.exit_code == 1);
    replay[k] = r.output;
    r = run_vbsim("oracle " + trace + " -q -o " + (dir / "o.jsonl").string() + threads);
    CHECK(r.exit_code == 1);
    oracle[k] = r.output;
    // A parent beyond the window: the first child whose parent is 2 rays back.
    r = run_vbsim("replay " + generated_trace(dir) + " -q --hitpoint ray --parent-window 2" + threads);
    CHECK(r.exit_code == 1);
    window[k] = r.output;
  }
  INFO(check[0]);
  // Every problem, each at its line (the comment and blank line move those after 5001 by 2).
  CHECK_THAT(check[0], Catch::Contains("damaged.jsonl:4501: ") && Catch::Contains("damaged.jsonl:6103: field 'id'") &&
                           Catch::Contains("warning [missing_expect]") &&
                           Catch::Contains("damaged.jsonl:9004: error [child_before_parent]") &&
                           Catch::Contains("damaged.jsonl:11004: "));
  CHECK_THAT(replay[0], Catch::Contains("damaged.jsonl:4501"));
  CHECK_THAT(oracle[0], Catch::Contains("damaged.jsonl:4501"));
  CHECK_THAT(window[0], Catch::Contains("--parent-window"));
  for (int k = 1; k < 4; ++k) {
    INFO("threads " << kThreadCounts[k]);
    CHECK(check[k] == check[0]);
    CHECK(replay[k] == replay[0]);
    CHECK(oracle[k] == oracle[0]);
    CHECK(window[k] == window[0]);
  }
}

TEST_CASE("a thread count of 0 or below is refused", "[system][threads][cli]") {
  const auto dir = scratch_dir("threads_refused");
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  for (const char* value : {"0", "-1", "-8"}) {
    for (const std::string& command :
         {"replay " + trace, "oracle " + trace + " -o " + (dir / "o.jsonl").string(), "check " + trace,
          "score " + trace}) {
      INFO(command << " --threads " << value);
      const RunResult r = run_vbsim(command + " -q --threads " + value);
      CHECK(r.exit_code == 2);
      CHECK_THAT(r.output, Catch::Contains("vbsim: usage error: option '--threads': must be >= 1"));
    }
  }
  CHECK(!std::filesystem::exists(dir / "o.jsonl"));
  const RunResult r = run_vbsim("replay " + trace + " -q --mode cycle --threads 2");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("option '--threads'") && Catch::Contains("cycle"));
}

TEST_CASE("the provenance leaves the thread count out of the command line", "[system][threads]") {
  const auto dir = scratch_dir("threads_provenance");
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const auto s = dir / "s.json";
  REQUIRE(run_vbsim("replay " + trace + " -q --threads=3 --stats " + s.string()).exit_code == 0);
  const auto command = nlohmann::json::parse(read_file(s))["provenance"]["command"];
  CHECK(command == nlohmann::json::array({VBSIM_BINARY, "replay", trace, "-q", "--stats", s.string()}));
}
