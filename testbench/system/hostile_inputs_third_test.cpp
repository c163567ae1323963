// Files and command lines from elsewhere, third round (docs/reliability.md):
// score refuses an output that names any input; a NUL byte inside a JSON
// string; numbers out of range on the command line and in a configuration;
// endless inputs; messages said once and named; one parent window.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"
#include "trace/parent_order_check.h"
#include "trace/parent_ray_store.h"

using namespace vbsim::test;

namespace {

const std::string kBunny = source_dir() + "/traces/bunny/bunny.obj";
const std::string kTrace = source_dir() + "/traces/bunny/paths.jsonl";

std::string header(const std::string& scene) {
  return "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"" + scene + "\"}\n";
}

/// The bundled trace's rays, without its header.
std::string bunny_rays() {
  const std::string text = read_file(kTrace);
  return text.substr(text.find('\n') + 1);
}

/// How often `needle` occurs in `text`.
size_t occurrences(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("score refuses an output that is a trace's scene, a merged table or another input", "[cli][hostile]") {
  const auto dir = scratch_dir("score_inputs");
  const auto scene = dir / "s.obj", family = dir / "family", trace = family / "t.jsonl", part = dir / "part.json";
  std::filesystem::create_directories(family);
  write_file(scene, read_file(kBunny));
  write_file(trace, header(scene.string()) + bunny_rays());
  write_file(part, "{\"not\": \"read\"}\n");
  const std::string scene_before = read_file(scene), trace_before = read_file(trace);
  const std::string run = " --methods tmin --testers three-half-plane -q";
  struct Case {
    std::string args, role;
  };
  const std::vector<Case> cases = {
      {"score " + trace.string() + run + " --out " + scene.string(), "option '--out'"},
      {"score " + family.string() + run + " --accuracy-md " + scene.string(), "option '--accuracy-md'"},
      {"score --merge " + part.string() + " --accuracy-md " + part.string(), "option '--accuracy-md'"},
      {"score --merge " + part.string() + " --out " + part.string(), "option '--out'"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const RunResult r = run_vbsim(c.args);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Catch::Contains("vbsim: usage error: " + c.role) &&
                             Catch::Contains("this run reads; refusing to overwrite it"));
  }
  CHECK(read_file(scene) == scene_before);
  CHECK(read_file(trace) == trace_before);
  CHECK(read_file(part) == "{\"not\": \"read\"}\n");
  std::filesystem::remove_all(dir);
}

TEST_CASE("a NUL byte inside a JSON string is an error naming the file, line and field", "[cli][hostile]") {
  const auto dir = scratch_dir("nul_strings");
  const auto kind = dir / "kind.jsonl", scene = dir / "scene.jsonl";
  std::string rays = bunny_rays();
  const size_t shadow = rays.find("\"kind\":\"shadow\"");
  REQUIRE(shadow != std::string::npos);
  const size_t line = 2 + static_cast<size_t>(std::count(rays.begin(), rays.begin() + shadow, '\n'));
  rays.replace(shadow, 15, "\"kind\":\"shadow\\u0000 not a kind\"");
  write_file(kind, header(kBunny) + rays);
  // The scene's name with a NUL after a file that exists: never opened.
  write_file(scene, header(kBunny + "\\u0000.ply") + bunny_rays());
  const std::string at_kind = kind.string() + ":" + std::to_string(line) + ": field 'kind': a NUL byte";
  const std::string at_scene = scene.string() + ":1: field 'scene': a NUL byte";
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {"check " + kind.string(), at_kind},
      {"replay " + kind.string() + " -q", at_kind},
      {"oracle " + kind.string() + " -q -o " + (dir / "o.jsonl").string(), at_kind},
      {"score " + kind.string() + " -q --methods tmin --testers three-half-plane", at_kind},
      {"convert " + kind.string() + " -o " + (dir / "c.jsonl").string(), at_kind},
      {"replay " + scene.string() + " -q", at_scene},
      {"check " + scene.string(), at_scene},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const RunResult r = run_vbsim(c.args);
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.output, Catch::Contains(c.expected));
  }
  CHECK_FALSE(std::filesystem::exists(dir / "c.jsonl"));  // convert wrote no "shadow"
  CHECK_FALSE(std::filesystem::exists(dir / "o.jsonl"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("numbers out of range on the command line are usage errors naming the option", "[cli][hostile]") {
  const auto dir = scratch_dir("option_ranges");
  const std::string png = (dir / "x.png").string();
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {"render " + kBunny + " -o " + png + " --seed -1", "option '--seed': -1 is negative"},
      {"render " + kBunny + " -o " + png + " --seed 99999999999999999999999",
       "option '--seed': 99999999999999999999999 is out of range"},
      {"gen paths --seed 010 -o " + (dir / "g").string(), "option '--seed': '010' has a leading 0"},
      {"replay " + kTrace + " --mode cycle --interval-stats " + (dir / "i.json").string() + " --interval -1",
       "option '--interval': -1 is negative"},
      {"replay " + kTrace + " --mode cycle --warmup-rays -1", "option '--warmup-rays': -1 is negative"},
      {"replay " + kTrace + " --mode cycle --timeline " + (dir / "t.json").string() +
           " --timeline-start 18446744073709551616",
       "option '--timeline-start': 18446744073709551616 is out of range"},
      {"reintersect --first 18446744073709551616", "option '--first': 18446744073709551616 is out of range"},
      {"check " + kTrace + " --max-per-check -1", "option '--max-per-check': -1 is negative"},
      {"bench --rays 99999999999999999999", "option '--rays': 99999999999999999999 is out of range"},
      {"replay " + kTrace + " --tmin-eps 1e-999", "option '--tmin-eps': 1e-999 is too small for a double"},
      // Float32 parameters: checked as the configuration field they set.
      {"replay " + kTrace + " --tmin-eps 1e-50",
       "option '--tmin-eps': field 'tmin_eps': 1e-50 is too small for a float32: it rounds to 0"},
      {"replay " + kTrace + " --vb-eps 1e300", "option '--vb-eps': field 'validity_bit.eps': 1e+300 is out of range"},
      {"replay " + kTrace + " --tmin-eps -1", "option '--tmin-eps': field 'tmin_eps': must be >= 0"},
      {"replay " + kTrace + " --tmin-eps nan", "option '--tmin-eps': 'nan' is not a decimal number"},
      {"reintersect --triangles 0", "option '--triangles': must be >= 1"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const RunResult r = run_vbsim(c.args + " -q");
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Catch::Contains("vbsim: usage error: " + c.expected));
  }
  CHECK(std::filesystem::is_empty(dir));  // refused before any work
  // Values in range still run; a float32 parameter reads as the config's does.
  CHECK(run_vbsim("replay " + kTrace + " -q --tmin-eps 1e-3 --method tmin").exit_code == 0);
  CHECK(run_vbsim("check " + kTrace + " -q --max-per-check +3").exit_code == 0);
  // A configuration's number that is not zero but reads as 0 names its field.
  const auto cfg = dir / "c.json";
  write_file(cfg, "{\"method\": \"tmin\",\n \"tmin_eps\": 1e-999}\n");
  RunResult r = run_vbsim("replay " + kTrace + " -q --config " + cfg.string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("vbsim: error: " + cfg.string() +
                                       ": field 'tmin_eps': 1e-999 is too small for a double: it rounds to 0"));
  write_file(cfg, "{\"method\": \"tmin\", \"tmin_eps\": 0e-999, \"offset_normal_eps\": 0.0}\n");  // zeros are zero
  r = run_vbsim("replay " + kTrace + " -q --config " + cfg.string());
  CHECK(r.exit_code == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("endless inputs are refused at a bound, naming the file", "[cli][hostile]") {
  struct Case {
    std::string args, expected;
  };
  const std::string ref = source_dir() + "/traces/bunny/paths.jsonl";
  const std::vector<Case> cases = {
      {"replay " + kTrace + " -q --config /dev/zero", "/dev/zero: longer than 64 MiB"},
      {"hw --tech /dev/zero", "/dev/zero: longer than 64 MiB"},
      {"score --merge /dev/zero -q", "/dev/zero: longer than 64 MiB"},
      {"check /dev/zero", "/dev/zero:1: longer than 16 MiB"},
      {"replay /dev/zero -q", "/dev/zero:1: longer than 16 MiB"},
      {"compare-reference /dev/zero " + ref + " -q", "/dev/zero:1: longer than 16 MiB"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    // 2 GB of address space: more than any of these needs, less than an
    // unbounded read takes before it fails (then "out of memory", not the bound).
    // AddressSanitizer reserves terabytes of shadow address space at start, so
    // its build runs without the limit (the message still shows the bound).
#if defined(__SANITIZE_ADDRESS__)
    const std::string limit;
#else
    const std::string limit = "ulimit -v 2000000; ";
#endif
    const RunResult r = run_command("bash -c '" + limit + std::string(VBSIM_BINARY) + " " + c.args + "' 2>&1");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Catch::Contains("vbsim: error: " + c.expected));
    CHECK(occurrences(r.output, "vbsim: error") == 1);
  }
}

TEST_CASE("a directory, a full stdout and help to a closed pipe are each said once, or not at all", "[cli][hostile]") {
  const auto dir = scratch_dir("messages");
  RunResult r = run_vbsim("replay " + kTrace + " -q --config " + dir.string());
  CHECK(r.exit_code == 1);
  CHECK(r.output == "vbsim: error: " + dir.string() + ": is a directory, not a JSON file\n");
  r = run_vbsim("hw --tech " + dir.string());
  CHECK(r.exit_code == 1);
  CHECK(r.output == "vbsim: error: " + dir.string() + ": is a directory, not a JSON file\n");
  // hw's text is longer than stdout's buffer: the write fails during the run.
  r = run_vbsim_raw("hw 2>&1 >/dev/full");
  CHECK(r.exit_code == 1);
  CHECK(r.output == "vbsim: error: standard output: No space left on device\n");
  // Help and version for a reader that has gone (`| head`): quiet, exit 0.
  for (const std::string args : {"replay --help", "--help", "--version"}) {
    INFO(args);
    // The reader (true) is gone before vbsim writes; vbsim's stderr goes to fd 3, read here.
    r = run_command("bash -c '{ (sleep 0.3; " + std::string(VBSIM_BINARY) + " " + args +
                    " 2>&3) | true; echo \"status ${PIPESTATUS[0]}\"; } 3>&1'");
    CHECK(r.output == "status 0\n");
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("check and the replays look for parents within one window, --parent-window", "[cli][hostile]") {
  CHECK(vbsim::ParentOrderCheck::kDefaultWindow == static_cast<size_t>(vbsim::ParentRayStore::kDefaultWindow));
  const auto dir = scratch_dir("parent_window");
  const auto stats = dir / "s.json";
  for (const std::string& window : {std::string(""), std::string(" --parent-window 5000")}) {
    INFO(window);
    REQUIRE(run_vbsim("replay " + kTrace + " -q --stats " + stats.string() + window).exit_code == 0);
    const auto j = nlohmann::json::parse(read_file(stats));
    CHECK(j["checks"]["window"] == (window.empty() ? 131072 : 5000));
  }
  // Ids out of order: check says how far back it looks for parents.
  const auto trace = dir / "t.jsonl";
  write_file(trace, header(kBunny) + "{\"id\":5,\"o\":[0,0,5],\"d\":[0,0,-1]}\n{\"id\":4,\"o\":[0,0,5],\"d\":[0,0,-1]}\n");
  for (const auto& [option, window] : {std::pair<std::string, std::string>{"", "131072"},
                                       {" --parent-window 1000", "1000"},
                                       {" --window 1000", "1000"}}) {
    INFO(option);
    const RunResult r = run_vbsim("check " + trace.string() + option);
    CHECK_THAT(r.output, Catch::Contains("parents are then checked only within the last " + window + " rays"));
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("the cycle-level summary gives every energy and area figure its unit", "[cli][hostile]") {
  // The line once ended "(... static; the method 26.32)": a number without a unit.
  const RunResult r = run_vbsim("replay " + kTrace + " --mode cycle -m offset-errbound");
  REQUIRE(r.exit_code == 0);
  const size_t energy = r.output.find("  energy ");
  REQUIRE(energy != std::string::npos);
  const std::string line = r.output.substr(energy, r.output.find('\n', energy) - energy);
  INFO(line);
  CHECK(line.find(" pJ/ray (") != std::string::npos);
  CHECK(line.find(" static; the method ") != std::string::npos);
  CHECK(line.find(" pJ/ray)") != std::string::npos);
  const size_t area = r.output.find("  area ");
  REQUIRE(area != std::string::npos);
  const std::string area_line = r.output.substr(area, r.output.find('\n', area) - area);
  INFO(area_line);
  CHECK(occurrences(area_line, " mm2") == 3);
}
