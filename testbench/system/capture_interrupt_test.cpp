// vbsim capture stopped and run side by side: Ctrl-C or SIGTERM to the process
// group ends it with 130 and `vbsim: interrupted`, leaving no trace and no
// shim files; two captures into one directory each finish whole (no fixed
// temporary names to collide on); the temporaries a killed capture left are
// removed by the next one when their process is gone.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;
namespace fs = std::filesystem;

namespace {

/// True once `dir` holds an entry whose name contains `fragment` (polled for up to a minute).
bool wait_for_entry(const fs::path& dir, const std::string& fragment) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().filename().string().find(fragment) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// A pid that no process has: a child that has exited and been reaped.
long gone_pid() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  return child;
}

int64_t trace_rays(const fs::path& trace) {
  std::istringstream in(read_file(trace));
  int64_t lines = 0;
  for (std::string line; std::getline(in, line);) lines += !line.empty();
  return lines - 1;  // the header
}

}  // namespace

TEST_CASE("Ctrl-C or SIGTERM to a capture's process group ends it with 130 and leaves nothing",
          "[cli][capture][interrupt]") {
  const auto dir = scratch_dir("capture_interrupt");
  for (const int sig : {SIGINT, SIGTERM}) {
    INFO("signal " << sig);
    const auto out = dir / (sig == SIGINT ? "int" : "term");
    const std::string err = (dir / (sig == SIGINT ? "int.err" : "term.err")).string();
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {  // a process group of its own, as a shell's job is
      setpgid(0, 0);
      if (!freopen(err.c_str(), "w", stderr)) _exit(126);
      execl(VBSIM_BINARY, VBSIM_BINARY, "capture", "-o", out.c_str(), "--", "sleep", "30", static_cast<char*>(nullptr));
      _exit(127);
    }
    setpgid(child, child);
    const bool started = wait_for_entry(out, "raw.partial-");
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the application runs
    kill(-child, sig);
    int status = 0;
    waitpid(child, &status, 0);
    REQUIRE(started);
    INFO(read_file(err));
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 130);
    CHECK_THAT(read_file(err), Catch::Contains("vbsim: interrupted"));
    CHECK(entries(out).empty());  // no trace, no shim files, no temporaries
  }
}

TEST_CASE("two captures into one directory both finish whole", "[cli][capture]") {
  const auto dir = scratch_dir("capture_twice");
  const auto out = dir / "cap";
  const std::string app = VBSIM_CAPTURE_TEST_APP;
  const std::string capture = std::string(VBSIM_BINARY) + " capture --allow-partial -o " + out.string() + " -- " +
                              app + " 2 ";
  const RunResult r = run_command("(" + capture + (dir / "a.txt").string() + " > " + (dir / "a.out").string() +
                                  " 2>&1; echo $? > " + (dir / "a.code").string() + ") & (" + capture +
                                  (dir / "b.txt").string() + " > " + (dir / "b.out").string() + " 2>&1; echo $? > " +
                                  (dir / "b.code").string() + ") & wait");
  INFO(read_file(dir / "a.out") << read_file(dir / "b.out"));
  CHECK(read_file(dir / "a.code") == "0\n");
  CHECK(read_file(dir / "b.code") == "0\n");
  CHECK(entries(out) == std::vector<std::string>{"capture.json", "embree_hits.jsonl", "scene.ply", "trace.jsonl"});
  const nlohmann::json report = nlohmann::json::parse(read_file(out / "capture.json"));
  CHECK(trace_rays(out / "trace.jsonl") == report["rays_in_trace"].get<int64_t>());
}

TEST_CASE("a capture removes the temporaries of killed captures whose process is gone", "[cli][capture]") {
  const auto dir = scratch_dir("capture_stale");
  const auto out = dir / "cap";
  fs::create_directories(out);
  const std::string dead = std::to_string(gone_pid()), alive = std::to_string(::getpid());
  write_file(out / ("trace.jsonl.partial-" + dead + "-0"), "half a trace");
  write_file(out / ("capture.json.partial-" + dead + "-3"), "{");
  fs::create_directories(out / ("raw.partial-" + dead + "-0"));
  write_file(out / ("raw.partial-" + dead + "-0") / "rays-1.0-0.bin", "x");
  write_file(out / ("scene.ply.partial-" + alive + "-0"), "a run still writing");  // its process runs: kept
  const std::string app = VBSIM_CAPTURE_TEST_APP;
  const RunResult r = run_vbsim("capture --allow-partial -o " + out.string() + " -- " + app + " 1 " +
                                (dir / "a.txt").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(entries(out) == std::vector<std::string>{"capture.json", "embree_hits.jsonl", "scene.ply",
                                                 "scene.ply.partial-" + alive + "-0", "trace.jsonl"});
}
