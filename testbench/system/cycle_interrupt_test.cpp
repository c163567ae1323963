// A long cycle-level replay on a terminal shows its progress line, and Ctrl-C
// (SIGINT) stops it: exit status 130, statistics marked partial with fewer
// rays than the trace, and a hits file holding exactly the finished rays and
// a last line marking it partial.
#include <catch2/catch.hpp>

#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

/// `count` camera rays from in front of the bunny toward it (most hit it).
void write_camera_trace(const std::filesystem::path& path, int count) {
  std::ofstream out(path);
  out << R"({"format":"vbsim-trace","version":1,"scene":")" << source_dir() << "/traces/bunny/bunny.obj\"}\n";
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> spread(-5.0f, 5.0f);
  char line[128];
  for (int i = 0; i < count; ++i) {
    std::snprintf(line, sizeof line, "{\"id\":%d,\"o\":[0,5,20],\"d\":[%.4f,%.4f,-20]}\n", i, spread(rng), spread(rng));
    out << line;
  }
}

/// Reads what the child wrote on the terminal for up to `ms` milliseconds (or
/// until it closes it); false when the terminal closed.
bool read_terminal(int fd, std::string& seen, int ms) {
  pollfd p{fd, POLLIN, 0};
  if (poll(&p, 1, ms) <= 0) return true;
  char buf[4096];
  const ssize_t n = read(fd, buf, sizeof buf);
  if (n <= 0) return false;  // EIO once the child has exited
  seen.append(buf, static_cast<size_t>(n));
  return true;
}

}  // namespace

TEST_CASE("Ctrl-C stops a cycle replay on a terminal and writes partial statistics", "[system][cycle]") {
  const auto dir = scratch_dir("cycle_interrupt");
  constexpr int kRays = 300000;
  write_camera_trace(dir / "cam.jsonl", kRays);
  const std::string stats = (dir / "s.json").string(), hits = (dir / "h.hits").string();

  int terminal = -1;
  const pid_t child = forkpty(&terminal, nullptr, nullptr, nullptr);
  REQUIRE(child >= 0);
  if (child == 0) {
    const std::string trace = (dir / "cam.jsonl").string();
    execl(VBSIM_BINARY, VBSIM_BINARY, "replay", trace.c_str(), "--mode", "cycle", "--stats", stats.c_str(), "--hits",
          hits.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait for the progress line, then interrupt.
  std::string seen;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  bool open = true;
  while (open && seen.find("ETA") == std::string::npos && std::chrono::steady_clock::now() < deadline)
    open = read_terminal(terminal, seen, 50);
  kill(child, SIGINT);
  while (open) open = read_terminal(terminal, seen, 1000);
  int status = 0;
  waitpid(child, &status, 0);
  close(terminal);

  INFO(seen);
  // The progress line: percentage of the trace's rays, and the time left.
  CHECK_THAT(seen, Catch::Contains("\rreplay (cycle)") && Catch::Contains("%") && Catch::Contains("/300000 rays") &&
                       Catch::Contains("ETA"));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  const auto s = nlohmann::json::parse(read_file(stats));
  CHECK(s["sim"]["partial"] == true);
  const uint64_t done = s["hw"]["rays"].get<uint64_t>();
  CHECK(done > 0);
  CHECK(done < static_cast<uint64_t>(kRays));
  // The header, one line per finished ray, then the line that marks the file partial.
  const std::string lines = read_file(hits);
  CHECK(static_cast<uint64_t>(std::count(lines.begin(), lines.end(), '\n')) == done + 2);
  const size_t last = lines.rfind('\n', lines.size() - 2);
  const auto marker = nlohmann::json::parse(lines.substr(last + 1));
  CHECK(marker["partial"] == true);
  CHECK(marker["rays"].get<uint64_t>() == done);
  CHECK(s["sim"]["rays_dropped"].get<uint64_t>() > 0);
}
