// vbsim capture of Embree loaded every way an application may load it
// (testbench/capture/embree_grid.h, the same rays each time): linked; dlopen'd
// as a local library with its functions looked up by dlsym; brought along by a
// plugin dlopen'd as a local library (as Python loads Open3D). Each gives the
// linked program's trace. What the shim cannot reach (dlmopen into a namespace
// of its own, Embree's functions defined by the program itself) is refused
// with a reason and a non-zero exit, never an abort, and no trace is written.
#include <catch2/catch.hpp>

#include <filesystem>

#include "capture_test_support.h"

using namespace vbsim::test;

namespace {

std::filesystem::path test_program(const std::string& name) {
  return std::filesystem::path(VBSIM_CAPTURE_TEST_APP).parent_path() / name;
}

/// `vbsim capture -o DIR/cap -- PROGRAM OUT ARGS`, the application's answers in DIR/app.txt.
RunResult capture(const std::filesystem::path& dir, const std::string& program, const std::string& args) {
  return run_vbsim("capture -o " + (dir / "cap").string() + " -- " + test_program(program).string() + " " +
                   (dir / "app.txt").string() + args);
}

}  // namespace

TEST_CASE("capture gives the linked program's trace when Embree is dlopened as a local library",
          "[cli][capture][loading]") {
  const auto linked = scratch_dir("capture_loading_linked");
  RunResult r = capture(linked, "vbsim_capture_grid_direct_app", "");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string plugin = test_program("libvbsim_capture_grid_plugin.so").string();
  for (const std::string& args : {std::string(" local"), " plugin " + plugin}) {
    const auto dir = scratch_dir("capture_loading_dlopen");
    RunResult d = capture(dir, "vbsim_capture_dlopen_app", args);
    INFO(args << "\n" << d.output);
    REQUIRE(d.exit_code == 0);
    CHECK(read_file(dir / "app.txt") == read_file(linked / "app.txt"));  // the shim changed no answer
    CHECK(trace_rays_text(dir / "cap" / "trace.jsonl") == trace_rays_text(linked / "cap" / "trace.jsonl"));
    CHECK(without_provenance(read_file(dir / "cap" / "scene.ply")) ==
          without_provenance(read_file(linked / "cap" / "scene.ply")));
    CHECK(read_file(dir / "cap" / "embree_hits.jsonl") == read_file(linked / "cap" / "embree_hits.jsonl"));
  }
  CHECK_THAT(r.output, Catch::Contains("vbsim capture: 481 rays from 1 thread"));  // 256 camera rays, 225 shadow rays
}

TEST_CASE("capture refuses Embree loaded with dlmopen before the application traces", "[cli][capture][loading]") {
  const auto dir = scratch_dir("capture_loading_dlmopen");
  RunResult r = capture(dir, "vbsim_capture_dlopen_app", " dlmopen");
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("cannot capture") && Catch::Contains("libembree3") &&
                           Catch::Contains("namespace of its own"));
  CHECK_THAT(r.output, !Catch::Contains("Aborted") && !Catch::Contains("signal"));
  CHECK(!std::filesystem::exists(dir / "cap" / "trace.jsonl"));
  CHECK(!std::filesystem::exists(dir / "app.txt"));  // ended before it traced
}

TEST_CASE("capture refuses a program with Embree's functions of its own with a reason", "[cli][capture][loading]") {
  const auto dir = scratch_dir("capture_loading_own_rtc");
  RunResult r = run_vbsim("capture -o " + (dir / "cap").string() + " -- " +
                          test_program("vbsim_capture_own_rtc_app").string());
  INFO(r.output);
  CHECK(r.exit_code == 1);
  // Refused before it runs: its executable defines rtcIntersect1 itself.
  CHECK_THAT(r.output, Catch::Contains("defines Embree's functions itself") &&
                           Catch::Contains("statically linked Embree"));
  CHECK(!std::filesystem::exists(dir / "cap" / "raw"));
  CHECK(!std::filesystem::exists(dir / "cap" / "trace.jsonl"));
  // Stripped of its symbols, it is told by Embree's device class in its bytes,
  // and refused before it runs all the same (it would print "100 misses").
  r = run_vbsim("capture -o " + (dir / "stripped").string() + " -- " +
                test_program("vbsim_capture_own_rtc_app_stripped").string());
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("holds Embree's code") && Catch::Contains("stripped of its symbols"));
  CHECK_THAT(r.output, !Catch::Contains("misses"));
  CHECK(!std::filesystem::exists(dir / "stripped" / "raw"));
  CHECK(!std::filesystem::exists(dir / "stripped" / "trace.jsonl"));
}
