// vbsim capture on Debian's embree-tools tutorials whose answers involve what
// a trace cannot hold (instances, curves, subdivision, user, grid, point and
// motion-blurred geometry, filter functions), 64x48, one thread. The capture
// must exit non-zero unless --allow-partial, leave the image unchanged, and
// mark every ray it cannot reproduce: replayed with method none, every ray
// left unmarked gives Embree's answer (the test's independent account), and
// among the marked rays some do not (the marks are not decoration).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "capture_test_support.h"
#include "trace/incomplete_reasons.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

int shell(const std::string& cmd) {
  const int status = std::system((cmd + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string tutorial_command(const std::string& name, const std::filesystem::path& image) {
  return name + " --size 64 48 --threads 1 -o " + image.string();
}

struct ReplayAnswer {
  int64_t prim = -2;  ///< -1: none
  double t = 0.0;
};

/// The replay's answer per ray id from a --hits file.
std::vector<ReplayAnswer> replay_answers(const std::filesystem::path& hits, std::size_t rays) {
  std::vector<ReplayAnswer> answers(rays);
  std::istringstream in(read_file(hits));
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line);
    if (!j.contains("id")) continue;  // the provenance line
    ReplayAnswer& a = answers.at(j["id"].get<std::size_t>());
    a.prim = j["prim"].get<int64_t>();
    if (a.prim >= 0) a.t = j["t"].get<double>();
  }
  return answers;
}

struct TutorialCapture {
  std::filesystem::path dir;  ///< the --allow-partial capture
  nlohmann::json report;
  int64_t marked = 0, marked_differing = 0, unmarked_differing = 0;
  std::set<std::string> reasons_in_trace;
};

/// Captures `name`, checks the exit codes, the image and the marks (none
/// unless `marks`); returns what it counted.
TutorialCapture capture_tutorial(const std::string& name, bool marks = true) {
  INFO("embree-tools (" << name << ") is installed by scripts/setup.sh");
  REQUIRE(shell("command -v " + name) == 0);
  const auto dir = scratch_dir("capture_incomplete_" + name);
  REQUIRE(shell(tutorial_command(name, dir / "plain.ppm")) == 0);

  // Without --allow-partial: a non-zero exit that says why, the marked trace written.
  const auto strict = dir / "strict";
  RunResult r = run_vbsim("capture -o " + strict.string() + " -- " + tutorial_command(name, strict / "image.ppm"));
  INFO(r.output);
  CHECK(r.exit_code == (marks ? 1 : 0));
  if (marks) CHECK_THAT(r.output, Catch::Contains("are incomplete") && Catch::Contains("--allow-partial"));
  CHECK(std::filesystem::exists(strict / "trace.jsonl"));

  const auto out = dir / "cap";
  r = run_vbsim("capture --allow-partial -o " + out.string() + " -- " + tutorial_command(name, out / "image.ppm"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("incomplete: "));
  CHECK(read_file(out / "image.ppm") == read_file(dir / "plain.ppm"));  // the capture changes nothing

  TutorialCapture c;
  c.dir = out;
  c.report = nlohmann::json::parse(read_file(out / "capture.json"));
  const std::vector<TraceRay> trace = read_trace(out / "trace.jsonl");
  const std::vector<nlohmann::json> embree = read_embree_hits(out / "embree_hits.jsonl", trace.size());
  r = run_vbsim("replay -q " + (out / "trace.jsonl").string() + " --method none --hits " + (out / "replay.hits").string());
  REQUIRE(r.exit_code == 0);
  const std::vector<ReplayAnswer> replayed = replay_answers(out / "replay.hits", trace.size());
  for (const TraceRay& tr : trace) {
    const nlohmann::json& e = embree[static_cast<std::size_t>(tr.id)];
    const ReplayAnswer& a = replayed[static_cast<std::size_t>(tr.id)];
    const int64_t got = a.prim;
    REQUIRE(got >= -1);
    // The same answer: occluded or not; the same triangle, or (a hit on the
    // shared edge of two triangles, which either tester may name) another
    // triangle at the same distance.
    bool same;
    if (e.contains("occluded")) {
      same = e["occluded"].get<bool>() == (got >= 0);
    } else if (e.contains("not_captured") || e["prim"].get<int64_t>() < 0 || got < 0) {
      same = !e.contains("not_captured") && e["prim"].get<int64_t>() == got;
    } else {
      const double t = e["t"].get<double>();
      same = e["prim"].get<int64_t>() == got || std::fabs(a.t - t) <= 1e-6 * t;
    }
    if (tr.incomplete != 0) {
      ++c.marked;
      c.marked_differing += !same;
      for (int k = 0; k < kIncompleteReasonCount; ++k)
        if (tr.incomplete & (1u << k)) c.reasons_in_trace.insert(incomplete_reason_name(k));
    } else {
      INFO("ray " << tr.id << ": Embree " << e.dump() << ", replay " << got);
      CHECK(same);
      c.unmarked_differing += !same;
    }
  }
  CHECK(c.report["incomplete"]["rays"] == c.marked);
  for (const std::string& reason : c.reasons_in_trace) CHECK(c.report["incomplete"]["by_reason"][reason] > 0);
  CHECK((c.marked > 0) == marks);
  CHECK(c.unmarked_differing == 0);
  return c;
}

}  // namespace

TEST_CASE("capture flattens instances into world-space triangles, every answer Embree's",
          "[cli][capture][instances]") {
  // instanced_geometry: a ground plane and four instances of one scene. Every
  // ray is checked against Embree on the flattened triangles; none differs
  // here, so none is marked, and the replay gives Embree's answer for every ray.
  const TutorialCapture c = capture_tutorial("instanced_geometry", false);
  CHECK(c.report["instances"]["flattened"] == true);
  CHECK(c.report["instances"]["rays_checked"] == c.report["rays_in_trace"]);
  CHECK(c.report["instances"]["flattened_answer_differs"] == 0);
  CHECK(c.report["hits_outside_captured_triangles"] == 0);
  int instances = 0;
  for (const auto& g : c.report["scene"]["geometries"])
    if (g["type"] == "instance") {
      ++instances;
      CHECK(g["status"] == "captured");
      CHECK(g["triangles"] > 0);
    }
  CHECK(instances == 4);
  // The shadow rays from hits on instances now have their parents.
  CHECK(c.report["links"]["unlinked_occluded"] == 0);
}

TEST_CASE("capture marks the rays that filter functions changed, replays leave them unscored, compare-reference "
          "lists every difference", "[cli][capture][incomplete]") {
  const TutorialCapture c = capture_tutorial("intersection_filter");
  CHECK(c.reasons_in_trace == std::set<std::string>{"filter"});
  CHECK(c.marked_differing > 0);
  bool any_filter = false;
  for (const auto& g : c.report["scene"]["geometries"]) any_filter |= g.contains("intersect_filter");
  CHECK(any_filter);

  // `vbsim check` counts them by reason.
  RunResult check = run_vbsim("check " + (c.dir / "trace.jsonl").string());
  CHECK_THAT(check.output, Catch::Contains(fmt::format("{} rays marked incomplete (filter {})", c.marked, c.marked)));

  // Scored, the marked rays are replayed but not judged unless asked.
  const std::string scored = (c.dir / "scored.jsonl").string();
  REQUIRE(run_vbsim("oracle -q " + (c.dir / "trace.jsonl").string() + " -o " + scored).exit_code == 0);
  int64_t unscored[2] = {};
  for (const bool ask : {false, true}) {
    const auto stats = c.dir / (ask ? "asked.json" : "default.json");
    const RunResult r = run_vbsim("replay -q " + scored + " --method none --stats " + stats.string() +
                                  (ask ? " --score-incomplete" : ""));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const auto s = nlohmann::json::parse(read_file(stats));
    CHECK(s["incomplete"]["excluded"] == (ask ? 0 : c.marked));
    CHECK(s["incomplete"]["scored"] == (ask ? c.marked : 0));
    CHECK(s["rays"] == c.report["rays_in_trace"]);
    unscored[ask] = s["verdicts"]["unscored"].get<int64_t>();
  }
  CHECK(unscored[0] - unscored[1] == c.marked);

  // Every ray where the replay differs from the renderer's Embree, with the oracle's verdict:
  // the same rays the test found above, all of them marked.
  const auto hits = c.dir / "scored.hits", differences = c.dir / "differences.jsonl";
  REQUIRE(run_vbsim("replay -q " + scored + " --method none --score-incomplete --hits " + hits.string()).exit_code == 0);
  RunResult r = run_vbsim("compare-reference " + hits.string() + " " + (c.dir / "embree_hits.jsonl").string() +
                          " -o " + differences.string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains(fmt::format("{} rays;", c.report["rays_in_trace"].get<int64_t>())) &&
                           Catch::Contains(fmt::format("; {} differ", c.marked_differing)));
  const std::vector<TraceRay> trace = read_trace(c.dir / "trace.jsonl");
  std::istringstream in(read_file(differences));
  int64_t listed = 0;
  for (std::string line; std::getline(in, line); ++listed) {
    const auto j = nlohmann::json::parse(line);
    CHECK(trace.at(j["id"].get<std::size_t>()).incomplete == kIncompleteFilter);
    CHECK(j["verdict"] != "unscored");
    CHECK(j.contains("replay"));
    CHECK(j.contains("reference"));
  }
  CHECK(listed == c.marked_differing);
  // Files of different traces are refused, naming the place.
  r = run_vbsim("compare-reference " + hits.string() + " " + (source_dir() + "/traces/bunny/paths.jsonl"));
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("paths.jsonl:"));
}

TEST_CASE("capture marks the rays whose answers involve curves, points and user geometry",
          "[cli][capture][incomplete]") {
  CHECK(capture_tutorial("curve_geometry").reasons_in_trace.count("curve") == 1);
  CHECK(capture_tutorial("point_geometry").reasons_in_trace.count("point") == 1);
  CHECK(capture_tutorial("user_geometry").reasons_in_trace.count("user") == 1);
}

TEST_CASE("capture marks the rays whose answers involve subdivision surfaces and grids",
          "[cli][capture][incomplete]") {
  CHECK(capture_tutorial("subdivision_geometry").reasons_in_trace.count("subdivision") == 1);
  CHECK(capture_tutorial("displacement_geometry").reasons_in_trace.count("subdivision") == 1);
  CHECK(capture_tutorial("interpolation").reasons_in_trace.count("subdivision") == 1);
  CHECK(capture_tutorial("lazy_geometry").reasons_in_trace.count("instance") == 1);
  CHECK(capture_tutorial("grid_geometry").reasons_in_trace.count("grid") == 1);
}

TEST_CASE("capture marks the rays whose answers involve motion-blurred geometry", "[cli][capture][incomplete]") {
  CHECK(capture_tutorial("motion_blur_geometry").marked > 0);
}

TEST_CASE("capture says why an application that loads Embree but traces no rays gives no trace",
          "[cli][capture][incomplete]") {
  REQUIRE(shell("command -v bvh_access") == 0);
  const auto dir = scratch_dir("capture_no_rays");
  const RunResult r = run_vbsim("capture -o " + (dir / "c").string() + " -- " + tutorial_command("bvh_access", dir / "x.ppm"));
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("ran with a shared libembree3") && Catch::Contains("no rays to trace"));
  CHECK_THAT(r.output, !Catch::Contains("statically linked"));
}
