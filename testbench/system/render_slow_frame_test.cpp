// A render whose first pixels show that the frame will take long says so on
// stderr, with its pace and the time left, terminal or not, rather than look
// hung: 100,000 stacked coplanar triangles render at a tenth of a second a
// pixel and more (45 minutes for 160x120 on the build machine). Its first rows
// miss the triangles and go fast, so the pace is that of the last pixels, not
// the average since the start (which warned only after 17 s, with "1:01 left").
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "run_vbsim.h"
#include "scene/ply_scene_writer.h"

using namespace vbsim::test;

TEST_CASE("a slow render warns of its pace and time left", "[render][cli]") {
  const auto dir = scratch_dir("render_slow_frame");
  const std::vector<vbsim::Triangle> stacked(100000, vbsim::Triangle{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}});
  vbsim::write_ply_scene((dir / "stacked.ply").string(), stacked);
  const std::string png = (dir / "s.png").string(), err = (dir / "err.txt").string();
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    if (!freopen(err.c_str(), "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(126);
    execl(VBSIM_BINARY, VBSIM_BINARY, "render", (dir / "stacked.ply").c_str(), "--size", "160x120", "-o", png.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(90);
  bool warned = false;
  while (!warned && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    warned = read_file(err).find("slow frame") != std::string::npos;
  }
  kill(child, SIGTERM);  // no need to wait 45 minutes
  int status = 0;
  waitpid(child, &status, 0);
  const std::string said = read_file(err);
  INFO(said);
  REQUIRE(warned);
  CHECK_THAT(said, Catch::Contains("vbsim render: warning: a slow frame: ") && Catch::Contains(" of 19200 pixels in ") &&
                       Catch::Contains(" s a pixel: about ") && Catch::Contains(" left at that pace"));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK_FALSE(std::filesystem::exists(png));

  // A frame that ends soon says nothing of the kind.
  const RunResult quick = run_vbsim("render " + source_dir() + "/traces/bunny/bunny.obj --size 16x12 -o " +
                                    (dir / "b.png").string());
  CHECK(quick.exit_code == 0);
  CHECK(quick.output.find("slow frame") == std::string::npos);
}
