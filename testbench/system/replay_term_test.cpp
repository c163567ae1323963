// SIGTERM, like Ctrl-C, stops a replay at the next ray: exit status 130,
// statistics marked partial, a hits file of whole lines (its header, a line
// per finished ray) ending with the line that marks it partial; and a trace whose parents lie beyond the parent
// window is refused at the child, never replayed with other origins.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>


#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

std::string header_line() {
  return "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"" + source_dir() + "/traces/bunny/bunny.obj\"}\n";
}

/// `count` camera rays toward the bunny, each followed by a shadow child.
std::string camera_and_child_rays(int count, int parent_distance) {
  std::string text = header_line();
  for (int i = 0; i < count; ++i)
    text += "{\"id\":" + std::to_string(i) + ",\"o\":[0,0.1,5],\"d\":[" + std::to_string((i % 97) * 1e-4) + ",0,-1]}\n";
  // Children of the rays `parent_distance` before the end.
  for (int i = 0; i < 3; ++i)
    text += "{\"id\":" + std::to_string(count + i) + ",\"parent\":" + std::to_string(count - parent_distance + i) +
            ",\"kind\":\"shadow\",\"o\":[0,0.1,0.05],\"d\":[0,1,0],\"parent_prim\":0,\"parent_t\":4.9}\n";
  return text;
}

}  // namespace

TEST_CASE("SIGTERM stops a replay and writes partial statistics", "[system][interrupt]") {
  const auto dir = scratch_dir("sigterm");
  write_file(dir / "cam.jsonl", camera_and_child_rays(400000, 10));
  const std::string trace = (dir / "cam.jsonl").string(), stats = (dir / "s.json").string(),
                    hits = (dir / "h.jsonl").string();
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    execl(VBSIM_BINARY, VBSIM_BINARY, "replay", trace.c_str(), "-q", "--method", "validity-bit", "--stats",
          stats.c_str(), "--hits", hits.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const bool replaying = wait_for_file(dir, "h.jsonl.partial-", 100000);  // rays are being replayed
  kill(child, SIGTERM);
  int status = 0;
  waitpid(child, &status, 0);
  REQUIRE(replaying);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  const auto s = nlohmann::json::parse(read_file(stats));
  CHECK(s["sim"]["partial"] == true);
  const uint64_t rays = s["rays"].get<uint64_t>();
  CHECK(rays > 0);
  CHECK(rays < 400003);
  const std::string lines = read_file(hits);
  REQUIRE(!lines.empty());
  CHECK(lines.back() == '\n');
  CHECK(static_cast<uint64_t>(std::count(lines.begin(), lines.end(), '\n')) == rays + 2);  // + header and marker
  const auto marker = nlohmann::json::parse(lines.substr(lines.rfind('\n', lines.size() - 2) + 1));
  CHECK(marker == nlohmann::json{{"partial", true}, {"rays", rays}});
}

TEST_CASE("a parent beyond the parent window is an error at the child", "[system][parents]") {
  const auto dir = scratch_dir("parent_window");
  write_file(dir / "t.jsonl", camera_and_child_rays(20, 10));
  const std::string trace = (dir / "t.jsonl").string();
  // Children 20..22 name parents 10..12, which are 10 rays back.
  for (const char* mode : {"functional", "cycle"}) {
    INFO(mode);
    RunResult r = run_vbsim(std::string("replay ") + trace + " -q --hitpoint ray --mode " + mode + " --parent-window 5");
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.output, Catch::Contains("t.jsonl:22") && Catch::Contains("'parent'") &&
                             Catch::Contains("parent 10") && Catch::Contains("--parent-window"));
    r = run_vbsim(std::string("replay ") + trace + " -q --hitpoint ray --mode " + mode + " --parent-window 10");
    CHECK(r.exit_code == 0);
  }
  RunResult r = run_vbsim("score " + trace + " -q --methods tmin --parent-window 5");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("t.jsonl:22"));
  r = run_vbsim("oracle " + trace + " -o " + (dir / "o.jsonl").string() + " --parent-window 5");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("t.jsonl:22"));
  r = run_vbsim("replay " + trace + " --parent-window 0");
  CHECK(r.exit_code != 0);
}
