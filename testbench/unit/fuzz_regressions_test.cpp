// The fuzz targets' checks (testbench/fuzz/fuzz_checks.h) on every seed of
// their corpora and on every input a fuzzer ever broke
// (testbench/fuzz/regressions/): each is read or refused with the reader's own
// error, never a crash, a stray exception or a broken invariant.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>

#include "../fuzz/fuzz_checks.h"

namespace fs = std::filesystem;

namespace {

struct Target {
  const char* name;
  const char* suffix;  ///< the scene loader picks the format by it
  void (*check)(const std::string&);
};

const Target kTargets[] = {
    {"text_trace", ".jsonl", vbsim::fuzz::check_text_trace}, {"binary_trace", ".vbt", vbsim::fuzz::check_binary_trace},
    {"rtcore_rays", ".bin", vbsim::fuzz::check_rtcore_rays}, {"config", ".json", vbsim::fuzz::check_config},
    {"scene_ply", ".ply", vbsim::fuzz::check_scene},         {"scene_obj", ".obj", vbsim::fuzz::check_scene},
};

}  // namespace

TEST_CASE("fuzz seeds and regressions are read or refused cleanly", "[fuzz]") {
  const fs::path fuzz = fs::path(VBSIM_SOURCE_DIR) / "testbench" / "fuzz";
  const fs::path scratch = fs::temp_directory_path() / ("vbsim_fuzz_regressions_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  int inputs = 0, regressions = 0;
  for (const Target& t : kTargets)
    for (const char* kind : {"corpus", "regressions"}) {
      const fs::path dir = fuzz / kind / t.name;
      if (!fs::is_directory(dir)) continue;
      for (const auto& e : fs::directory_iterator(dir)) {
        INFO(t.name << ": " << e.path().string());
        const fs::path copy = scratch / (std::string("input") + t.suffix);
        fs::copy_file(e.path(), copy, fs::copy_options::overwrite_existing);
        CHECK_NOTHROW(t.check(copy.string()));
        ++inputs;
        regressions += std::string(kind) == "regressions";
      }
    }
  fs::remove_all(scratch);
  CHECK(inputs - regressions >= 15);  // the committed seeds
  CHECK(regressions >= 1);
}
