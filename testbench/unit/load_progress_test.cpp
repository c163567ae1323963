// Progress while a scene loads and its BVH builds: the loader and the builder
// tell a WorkProgress each step in order, with counts that grow to the step's
// total; a meter draws a step without a count as its name and the time.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <vector>

#include "progress/work_progress.h"
#include "scene/bvh.h"
#include "scene/scene.h"

using namespace vbsim;

namespace {

struct Step {
  std::string name, unit;
  uint64_t total = 0;
  std::vector<uint64_t> done;
};

/// Records every step and count.
class RecordingProgress final : public WorkProgress {
 public:
  void begin(const std::string& step, uint64_t total, const std::string& unit) override {
    steps.push_back({step, unit, total, {}});
  }
  void update(uint64_t done) override {
    REQUIRE(!steps.empty());
    steps.back().done.push_back(done);
  }
  std::vector<Step> steps;
};

/// Counts never fall and never pass the total (when there is one).
void check_counts(const Step& s) {
  INFO(s.name);
  for (size_t i = 0; i < s.done.size(); ++i) {
    if (i > 0) CHECK(s.done[i] >= s.done[i - 1]);
    if (s.total > 0) CHECK(s.done[i] <= s.total);
  }
}

}  // namespace

TEST_CASE("load progress: an OBJ scene is read, checked and read again as triangles", "[scene][progress]") {
  RecordingProgress progress;
  const Scene scene = load_scene(std::string(VBSIM_SOURCE_DIR) + "/traces/bunny/bunny.obj", std::nullopt, &progress);
  REQUIRE(progress.steps.size() == 3);
  CHECK(progress.steps[0].name == "reading");
  CHECK(progress.steps[1].name == "checking");
  CHECK(progress.steps[2].name == "reading triangles");
  for (const Step& s : progress.steps) {
    CHECK(s.unit == "MB");
    CHECK(s.total == 1);  // the bunny is under a megabyte
    CHECK(!s.done.empty());
    check_counts(s);
  }
  CHECK(progress.steps[0].done.back() == 1);  // the whole file read

  RecordingProgress wuson;  // not a plain file: assimp reads it, a step without a count
  load_scene(std::string(VBSIM_SOURCE_DIR) + "/traces/wuson/WusonOBJ.obj", std::nullopt, &wuson);
  REQUIRE(wuson.steps.size() == 3);
  CHECK(wuson.steps[2].name == "reading with assimp");
  CHECK(wuson.steps[2].total == 0);
  CHECK(wuson.steps[2].unit.empty());

  RecordingProgress build;
  const Bvh bvh = build_bvh(scene, {}, &build);
  REQUIRE(build.steps.size() == 1);
  CHECK(build.steps[0].name == "building the BVH");
  CHECK(build.steps[0].unit == "triangles");
  CHECK(build.steps[0].total == 3674);
  check_counts(build.steps[0]);
  CHECK(bvh.tris.size() == 3674);
  CHECK(build_bvh(scene).nodes.size() == bvh.nodes.size());  // watching changes nothing
}

TEST_CASE("load progress: a meter shows each step on its own line, cleared at the next", "[progress]") {
  std::FILE* out = std::tmpfile();
  REQUIRE(out != nullptr);
  {
    MeterWorkProgress meter("scene", out);
    meter.begin("reading", 858, "MB");
    meter.update(400);
    meter.begin("building the BVH", 0, "");
  }
  std::rewind(out);
  std::string text;
  for (int c; (c = std::fgetc(out)) != EOF;) text += static_cast<char>(c);
  std::fclose(out);
  CHECK_THAT(text, Catch::Contains("scene: reading    0.0%  0/858 MB"));
  CHECK_THAT(text, Catch::Contains("scene: building the BVH  0:0"));
  CHECK(text.back() == '\r');  // the last line cleared

  MeterWorkProgress silent("scene", nullptr);  // no terminal: nothing drawn, nothing fails
  silent.begin("reading", 1, "MB");
  silent.update(1);
}
