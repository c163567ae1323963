// vbsim capture on testbench/capture/embree_exclusion_app.cpp, which traces as
// Blender's Cycles does: children start at the barycentric hit point with no
// offset and a filter function rejects the primitive they start from. The
// shim records what the filters rejected; a ray whose only rejections are its
// parent's primitive is scoreable (primid reproduces it), any other rejection
// (an alpha cutout) leaves the ray marked `filter`. Shadow rays are intersect
// queries with a finite tfar.
#include <catch2/catch.hpp>

#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "capture_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

struct ExclusionCapture {
  RunResult capture;
  nlohmann::json report;
  std::filesystem::path dir, out;
  bool same_output = false;  ///< the app wrote the same answers with and without the shim
};

ExclusionCapture capture_mode(const std::string& mode, const std::string& options = "") {
  const auto app = std::filesystem::path(VBSIM_CAPTURE_TEST_APP).parent_path() / "vbsim_capture_exclusion_app";
  ExclusionCapture c;
  c.dir = scratch_dir("capture_exclusion_" + mode);
  c.out = c.dir / "cap";
  const RunResult plain = run_command(fmt::format("{} {} {}", app.string(), mode, (c.dir / "plain.txt").string()));
  REQUIRE(plain.exit_code == 0);
  c.capture = run_vbsim(fmt::format("capture {} -o {} -- {} {} {}", options, c.out.string(), app.string(), mode,
                                    (c.dir / "captured.txt").string()));
  c.report = nlohmann::json::parse(read_file(c.out / "capture.json"));
  c.same_output = read_file(c.dir / "plain.txt") == read_file(c.dir / "captured.txt");
  return c;
}

/// Rays of the capture where a primid replay differs from the application's Embree.
int64_t primid_differences(const ExclusionCapture& c) {
  const std::string trace = (c.out / "trace.jsonl").string(), scored = (c.dir / "scored.jsonl").string();
  const std::string hits = (c.dir / "primid.hits").string(), diff = (c.dir / "diff.jsonl").string();
  REQUIRE(run_vbsim(fmt::format("oracle {} -o {}", trace, scored)).exit_code == 0);
  REQUIRE(run_vbsim(fmt::format("replay {} --method primid --hits {}", scored, hits)).exit_code == 0);
  const RunResult cmp = run_vbsim(fmt::format("compare-reference {} {} -o {}", hits, (c.out / "embree_hits.jsonl").string(), diff));
  INFO(cmp.output);
  REQUIRE(cmp.exit_code == 0);
  int64_t n = 0;
  for (char ch : read_file(diff)) n += ch == '\n';
  return n;
}

}  // namespace

TEST_CASE("capture: a renderer's primitive-ID self-exclusion by filter functions leaves every ray scoreable",
          "[cli][capture][filter]") {
  for (const std::string mode : {"geometry", "context", "packet"}) {
    DYNAMIC_SECTION(mode) {
      const ExclusionCapture c = capture_mode(mode);
      INFO(c.capture.output);
      REQUIRE(c.capture.exit_code == 0);
      CHECK(c.same_output);
      const auto& rep = c.report;
      const int64_t rays = rep["rays_in_trace"];
      CHECK(rep["incomplete"]["rays"] == 0);
      // Every child re-meets its parent's triangle at t ~ 0 or leaves it: many are rejected.
      CHECK(rep["self_excluded"].get<int64_t>() > rays / 10);
      CHECK(rep["links"]["unlinked_intersect"] == 16 * 12);  // the camera rays, and no other
      CHECK(rep["kinds"]["shadow"].get<int64_t>() > 0);     // finite tfar toward the light
      CHECK(primid_differences(c) == 0);
      // What the filter rejected is in embree_hits.jsonl, naming the parent.
      const auto trace = read_trace(c.out / "trace.jsonl");
      const auto hits = read_embree_hits(c.out / "embree_hits.jsonl", trace.size());
      int64_t named = 0;
      for (std::size_t i = 0; i < trace.size(); ++i)
        if (hits[i].contains("filter_rejected")) {
          CHECK(hits[i]["filter_rejected"]["parent"] == true);
          CHECK(trace[i].parent >= 0);
          ++named;
        }
      CHECK(named == rep["self_excluded"].get<int64_t>());
    }
  }
}

TEST_CASE("capture: filter functions that reject other geometry leave those rays marked filter, the rest scored",
          "[cli][capture][filter]") {
  const ExclusionCapture c = capture_mode("transparent");
  INFO(c.capture.output);
  CHECK(c.capture.exit_code == 1);  // incomplete rays without --allow-partial
  CHECK(c.same_output);
  const auto& rep = c.report;
  const int64_t marked = rep["incomplete"]["by_reason"].value("filter", 0);
  CHECK(marked > 0);
  CHECK(rep["incomplete"]["rays"] == marked);
  const auto trace = read_trace(c.out / "trace.jsonl");
  const auto hits = read_embree_hits(c.out / "embree_hits.jsonl", trace.size());
  int64_t cut = 0;
  for (std::size_t i = 0; i < trace.size(); ++i) {
    const bool rejected_other =
        hits[i].contains("filter_rejected") && hits[i]["filter_rejected"]["parent"] == false;
    const bool is_marked = trace[i].incomplete != 0;
    // A ray is marked exactly when its filters rejected something but its parent's primitive only
    // (a second rejected primitive leaves the record naming the first and the ray marked).
    if (rejected_other) CHECK(is_marked);
    if (!hits[i].contains("filter_rejected")) CHECK(!is_marked);
    cut += rejected_other;
  }
  CHECK(cut > 0);
  // The rays not marked still replay to the application's answer with primid.
  CHECK(primid_differences(c) <= marked);
}

TEST_CASE("capture: a ray that starts on a surface but links to no parent is marked unlinked, never scored as a "
          "camera ray", "[cli][capture][filter]") {
  // With no tolerance, children at the barycentric hit point (a few ulps from o + t d) link to nothing.
  const ExclusionCapture c = capture_mode("geometry", "--allow-partial --link-ulps 0 --link-rejected-ulps 0 --link-offset 0");
  INFO(c.capture.output);
  REQUIRE(c.capture.exit_code == 0);
  const auto& rep = c.report;
  const int64_t unlinked = rep["links"]["unlinked_intersect"];
  CHECK(unlinked > 16 * 12 + 50);
  const int64_t marked = rep["incomplete"]["by_reason"].value("unlinked", 0);
  CHECK(marked == unlinked - 16 * 12);  // every unlinked ray but the camera rays from the eye
  const auto trace = read_trace(c.out / "trace.jsonl");
  for (const TraceRay& r : trace)
    if (r.parent < 0) CHECK((r.incomplete != 0) == (r.o != Vec3f{0.0f, -4.0f, 0.5f}));
}

TEST_CASE("score: the renderer row judges the capturing renderer's own answers, and a trace without them is refused",
          "[cli][capture][filter][score]") {
  const ExclusionCapture c = capture_mode("geometry");
  REQUIRE(c.capture.exit_code == 0);
  REQUIRE(primid_differences(c) == 0);  // also writes scored.jsonl
  const auto json_path = c.dir / "score.json";
  const RunResult r = run_vbsim(fmt::format("score {} --methods renderer,primid --testers moller-trumbore --out {}",
                                            (c.dir / "scored.jsonl").string(), json_path.string()));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const auto table = nlohmann::json::parse(read_file(json_path));
  nlohmann::json renderer, primid;
  for (const auto& row : table["rows"])
    if (row["kind"] == "all") (row["method"] == "renderer" ? renderer : primid) = row;
  REQUIRE(renderer.is_object());
  REQUIRE(primid.is_object());
  // The application's answers are primid's ray for ray (above), so their verdicts are too.
  CHECK(renderer["counts"] == primid["counts"]);
  CHECK(renderer["config"]["answers"] == "reference");
  CHECK(renderer["counts"]["correct"].get<int64_t>() > 0);

  // A trace that carries no renderer's answers: an error naming the ray, no row.
  const RunResult bad = run_vbsim(fmt::format("score {}/traces/bunny/paths.jsonl --methods renderer -q",
                                              source_dir()));
  CHECK(bad.exit_code == 1);
  CHECK_THAT(bad.output, Catch::Contains("carries no reference answer"));
}
