// vbsim capture of an application that exec()s another Embree program under
// its pid (testbench/capture/embree_exec_app.cpp, through execvp, execv and
// execl in turn): every image writes files of its own, so every ray is in the
// trace or counted as not captured, whichever image traced the most.
#include <catch2/catch.hpp>

#include <filesystem>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

std::string exec_app() {
  return (std::filesystem::path(VBSIM_CAPTURE_TEST_APP).parent_path() / "vbsim_capture_exec_app").string();
}

/// The pids the application wrote, one line "image PID RAYS" per image.
std::set<long> app_pids(const std::filesystem::path& account) {
  std::set<long> pids;
  std::istringstream in(read_file(account));
  std::string word;
  long pid = 0, rays = 0;
  while (in >> word >> pid >> rays) pids.insert(pid);
  return pids;
}

int64_t trace_rays(const std::filesystem::path& trace) {
  std::istringstream in(read_file(trace));
  int64_t lines = 0;
  for (std::string line; std::getline(in, line);) lines += !line.empty();
  return lines - 1;  // the header
}

}  // namespace

TEST_CASE("capture keeps apart the rays of every program an application exec()s under its pid", "[cli][capture]") {
  const auto dir = scratch_dir("capture_exec");
  SECTION("the first image traced the most: the others are counted, each as its own image") {
    const auto out = dir / "first";
    const RunResult r = run_vbsim("capture -o " + out.string() + " -- " + exec_app() + " " +
                                  (out / "app.txt").string() + " 9000 1498 600 300");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const std::set<long> pids = app_pids(out / "app.txt");
    REQUIRE(pids.size() == 1);  // one process, four images
    const nlohmann::json report = nlohmann::json::parse(read_file(out / "capture.json"));
    CHECK(report["rays_in_trace"] == 9000);
    CHECK(trace_rays(out / "trace.jsonl") == 9000);
    CHECK(report["pid"] == *pids.begin());
    CHECK(report["image"] == 0);
    const nlohmann::json& others = report["not_captured"]["other_processes"];
    REQUIRE(others.size() == 3);
    for (int k = 0; k < 3; ++k) {
      CHECK(others[k]["pid"] == *pids.begin());
      CHECK(others[k]["image"] == k + 1);
      CHECK(others[k]["rays"] == std::vector<int>{1498, 600, 300}[static_cast<size_t>(k)]);
    }
    CHECK(report["not_captured"]["other_process_rays"] == 2398);
    CHECK_THAT(r.output, Catch::Contains("9000 rays") && Catch::Contains("2398 rays of other processes"));
  }
  SECTION("an exec'd image traced the most: its rays are the trace") {
    const auto out = dir / "later";
    const RunResult r = run_vbsim("capture -o " + out.string() + " -- " + exec_app() + " " +
                                  (out / "app.txt").string() + " 100 5000");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const nlohmann::json report = nlohmann::json::parse(read_file(out / "capture.json"));
    CHECK(report["rays_in_trace"] == 5000);
    CHECK(report["image"] == 1);
    CHECK(report["not_captured"]["other_process_rays"] == 100);
    CHECK(trace_rays(out / "trace.jsonl") == 5000);
  }
}
