// Outputs a run can trust: an output naming an input is refused before any
// work and the input stays intact; write errors exit non-zero; a run that
// fails leaves no output that looks whole; inputs may be pipes.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {
const std::string kTrace = source_dir() + "/traces/bunny/paths.jsonl";

std::string header_line() {
  return "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"" + source_dir() + "/traces/bunny/bunny.obj\"}\n";
}

/// The bundled trace with its scene named by an absolute path, so that a copy works anywhere.
std::string bunny_trace_text() {
  const std::string text = read_file(kTrace);
  return header_line() + text.substr(text.find('\n') + 1);
}

/// Names in `dir` (files left behind, temporaries included).
std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

TEST_CASE("an output naming an input is refused and the input stays whole", "[cli][outputs]") {
  const auto dir = scratch_dir("clash");
  const auto trace = dir / "t.jsonl";
  write_file(trace, bunny_trace_text());
  const std::string before = read_file(trace);
  std::filesystem::create_symlink(trace, dir / "link.jsonl");

  RunResult r = run_vbsim("replay " + trace.string() + " --hits " + trace.string());
  CHECK(r.exit_code != 0);
  CHECK(r.exit_code == 2);  // a usage error, found before any work
  CHECK_THAT(r.output, Catch::Contains("option '--hits'") && Catch::Contains("also the trace"));
  r = run_vbsim("replay " + trace.string() + " --stats " + (dir / "link.jsonl").string());  // the same file by a link
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("option '--stats'"));
  r = run_vbsim("replay " + trace.string() + " --stats " + (dir / "s.json").string() + " --hits " + (dir / "s.json").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("also the output of option '--stats'"));
  r = run_vbsim("convert " + trace.string() + " -o " + (dir / "." / "t.jsonl").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("also the input"));
  r = run_vbsim("oracle " + trace.string() + " -o " + trace.string());
  CHECK(r.exit_code != 0);
  r = run_vbsim("replay " + trace.string() + " --hits " + source_dir() + "/traces/bunny/bunny.obj");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("also the scene"));
  const auto mesh = dir / "box.obj";
  write_file(mesh, read_file(source_dir() + "/traces/bunny/bunny.obj"));
  r = run_vbsim("watertight " + mesh.string() + " -q --json " + mesh.string());
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("option '--json'") && Catch::Contains("also the mesh"));
  CHECK(read_file(mesh) == read_file(source_dir() + "/traces/bunny/bunny.obj"));
  std::filesystem::remove(mesh);
  CHECK(read_file(trace) == before);
  CHECK(names_in(dir) == std::vector<std::string>{"link.jsonl", "t.jsonl"});
}

TEST_CASE("write errors exit non-zero and name the output", "[cli][outputs]") {
  if (!std::filesystem::exists("/dev/full")) return;
  RunResult r = run_vbsim("replay " + kTrace + " -q --stats /dev/full");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("/dev/full") && Catch::Contains("write failed"));
  r = run_vbsim("replay " + kTrace + " -q --hits /dev/full");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("/dev/full"));
  r = run_vbsim("replay " + kTrace + " -q --mode cycle --timeline /dev/full");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("/dev/full"));
  r = run_vbsim("convert " + kTrace + " -o /dev/full");
  CHECK(r.exit_code != 0);
  for (const char* other : {"hw --statistics --json /dev/full", "watertight -q --json /dev/full",
                            "reintersect -q --triangles 2 --children 1 --json /dev/full"}) {
    r = run_vbsim(other);
    INFO(other << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Catch::Contains("/dev/full") && Catch::Contains("write failed"));
  }
  // In-place outputs that do not fail are fine, even twice in one run.
  r = run_vbsim("replay " + kTrace + " -q --stats /dev/null --hits /dev/null");
  CHECK(r.exit_code == 0);
}

TEST_CASE("a failed run leaves no output that looks whole", "[cli][outputs]") {
  const auto dir = scratch_dir("failed_run");
  // A trace whose last ray is bad: everything before it was read and written.
  std::string text = header_line();
  for (int i = 0; i < 50; ++i) text += "{\"id\":" + std::to_string(i) + ",\"o\":[0,0.1,5],\"d\":[0,0,-1]}\n";
  text += "{\"id\":50,\"o\":[0,0.1,5],\"d\":[0,0,0]}\n";
  write_file(dir / "bad.jsonl", text);
  const auto stats = dir / "s.json", hits = dir / "h.jsonl";
  write_file(stats, "previous stats\n");
  RunResult r = run_vbsim("replay " + (dir / "bad.jsonl").string() + " --stats " + stats.string() + " --hits " +
                          hits.string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("bad.jsonl:52"));
  CHECK(read_file(stats) == "previous stats\n");  // untouched, not truncated
  CHECK_FALSE(std::filesystem::exists(hits));
  r = run_vbsim("convert " + (dir / "bad.jsonl").string() + " -o " + (dir / "out.vbt").string());
  CHECK(r.exit_code != 0);
  r = run_vbsim("oracle " + (dir / "bad.jsonl").string() + " -o " + (dir / "out.jsonl").string());
  CHECK(r.exit_code != 0);
  CHECK(names_in(dir) == std::vector<std::string>{"bad.jsonl", "s.json"});  // no temporaries either
}

TEST_CASE("truncated traces name the line or record where they stop", "[cli][outputs]") {
  const auto dir = scratch_dir("truncated");
  RunResult r = run_vbsim("convert " + kTrace + " -o " + (dir / "t.vbt").string());
  REQUIRE(r.exit_code == 0);
  std::string bytes = read_file(dir / "t.vbt");
  bytes.resize(bytes.size() - 40);
  write_file(dir / "cut.vbt", bytes);
  r = run_vbsim("replay " + (dir / "cut.vbt").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("record 1007") && Catch::Contains("truncated"));
  std::string text = bunny_trace_text();
  text.resize(text.size() - 30);
  write_file(dir / "cut.jsonl", text);
  r = run_vbsim("replay " + (dir / "cut.jsonl").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("cut.jsonl:1009"));
}

TEST_CASE("a trace and a config may be pipes, read once", "[cli][outputs]") {
  const auto dir = scratch_dir("pipes");
  const std::string trace = (dir / "t.jsonl").string();
  write_file(trace, bunny_trace_text());
  write_file(dir / "c.json", "{\"method\": \"validity-bit\", \"hw\": {\"cores\": 2}}\n");
  const std::string direct = (dir / "direct.json").string(), piped = (dir / "piped.json").string();
  RunResult r = run_vbsim("replay " + trace + " -q --mode cycle --config " + (dir / "c.json").string() +
                          " --stats " + direct);
  REQUIRE(r.exit_code == 0);
  // The trace on standard input and the config through a second pipe: the
  // config is read twice (method, hw) but opened once.
  r = run_vbsim_bash("replay /dev/stdin -q --mode cycle --config <(cat " + (dir / "c.json").string() + ") --stats " + piped +
                " < " + trace);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  auto a = nlohmann::json::parse(read_file(direct)), b = nlohmann::json::parse(read_file(piped));
  CHECK(b["config"]["hw"]["cores"] == 2);
  int pipes = 0;  // the config's pipe has no checksum to record (stdin from a file has)
  for (const auto& in : b["provenance"]["inputs"]) pipes += in["sha256"].is_null();
  CHECK(pipes == 1);
  for (auto* j : {&a, &b}) {
    j->erase("sim");
    j->erase("provenance");
    (*j)["config"].erase("trace");
    (*j)["config"].erase("scene");
  }
  CHECK(a == b);
  r = run_vbsim("convert /dev/stdin -o " + (dir / "p.vbt").string() + " < " + trace);
  CHECK(r.exit_code == 0);
}
