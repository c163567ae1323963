// vbsim capture on testbench/capture/embree_instances_app.cpp, which instances
// one scene (two triangles and a quad) four times, each transform given to
// rtcSetGeometryTransform in another format: the flattened triangles must be
// the app's meant transform of the instanced scene's (whatever the format),
// every ray must be checked against them, and the replay must give Embree's
// answer for every ray that is not marked.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "capture_test_support.h"
#include "scene/scene.h"
#include "trace/incomplete_reasons.h"
#include "trace/trace_file.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

struct AppInstance {
  unsigned geom_id;
  std::string format;
  float m[12];
};

Vec3f apply(const float m[12], Vec3f p) {
  const double x = p.x, y = p.y, z = p.z;
  return {static_cast<float>(double(m[0]) * x + double(m[1]) * y + double(m[2]) * z + double(m[3])),
          static_cast<float>(double(m[4]) * x + double(m[5]) * y + double(m[6]) * z + double(m[7])),
          static_cast<float>(double(m[8]) * x + double(m[9]) * y + double(m[10]) * z + double(m[11]))};
}

}  // namespace

TEST_CASE("capture flattens instances set in every transform format Embree accepts", "[cli][capture][instances]") {
  const auto app = std::filesystem::path(VBSIM_CAPTURE_TEST_APP).parent_path() / "vbsim_capture_instances_app";
  const auto dir = scratch_dir("capture_instances");
  const auto out = dir / "cap";
  RunResult r = run_vbsim("capture --allow-partial -o " + out.string() + " -- " + app.string() + " " +
                          (dir / "app.txt").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);

  std::vector<AppInstance> instances;
  std::istringstream in(read_file(dir / "app.txt"));
  for (std::string word; in >> word;) {
    if (word == "instance") {
      AppInstance a;
      std::string f;
      in >> a.geom_id >> a.format;
      for (float& x : a.m) in >> f, x = std::strtof(f.c_str(), nullptr);  // hex floats, exact
      instances.push_back(a);
    } else if (word == "unsupported") {
      in >> word;  // a format Embree refused (the app left that instance out)
    }
  }
  // The three formats Embree 3 documents; its 4x4 row-major is refused here.
  REQUIRE(instances.size() >= 3);

  const nlohmann::json report = nlohmann::json::parse(read_file(out / "capture.json"));
  const Scene scene = load_scene((out / "scene.ply").string());
  // The instanced scene in its numbering: the square's two triangles, then the
  // quad as Embree splits it, (v0, v1, v3) and (v2, v3, v1).
  const Vec3f s[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Vec3f q[4] = {{0, 0, 0.5f}, {0.5f, 0, 0.5f}, {0.5f, 0.5f, 0.5f}, {0, 0.5f, 0.5f}};
  const Triangle child[4] = {{s[0], s[1], s[2]}, {s[0], s[2], s[3]}, {q[0], q[1], q[3]}, {q[2], q[3], q[1]}};
  for (const AppInstance& a : instances) {
    INFO("instance " << a.geom_id << " set as " << a.format);
    const nlohmann::json* g = nullptr;
    for (const auto& e : report["scene"]["geometries"])
      if (e["geomID"] == a.geom_id) g = &e;
    REQUIRE(g);
    CHECK((*g)["type"] == "instance");
    REQUIRE((*g)["status"] == "captured");
    REQUIRE((*g)["triangles"] == 4);
    const int64_t first = (*g)["first_triangle"];
    for (int k = 0; k < 4; ++k) {
      const Triangle& t = scene.triangles[static_cast<std::size_t>(first + k)];
      CHECK(t.v0 == apply(a.m, child[k].v0));
      CHECK(t.v1 == apply(a.m, child[k].v1));
      CHECK(t.v2 == apply(a.m, child[k].v2));
    }
  }
  // Every ray was held against the flattened triangles; the ones that differ are marked.
  CHECK(report["instances"]["rays_checked"] == report["rays_in_trace"]);
  CHECK(report["instances"]["flattened_answer_differs"] == report["incomplete"]["rays"]);
  CHECK(report["hits_outside_captured_triangles"] == 0);

  // The replay gives Embree's answer for every ray not marked.
  const auto hits = out / "replay.hits";
  REQUIRE(run_vbsim("replay -q " + (out / "trace.jsonl").string() + " --method none --hits " + hits.string()).exit_code == 0);
  r = run_vbsim("compare-reference -q " + hits.string() + " " + (out / "embree_hits.jsonl").string());
  const std::vector<TraceRay> trace = read_trace(out / "trace.jsonl");
  std::istringstream diffs(r.output);
  int64_t differing = 0;
  for (std::string line; std::getline(diffs, line); ++differing) {
    const auto j = nlohmann::json::parse(line);
    CHECK(trace.at(j["id"].get<std::size_t>()).incomplete != 0);
  }
  CHECK(differing <= report["incomplete"]["rays"].get<int64_t>());
  CHECK(trace.size() > 9000);

  // Embree's answers are in the trace too (`reference`), the same as embree_hits.jsonl.
  const std::vector<nlohmann::json> embree = read_embree_hits(out / "embree_hits.jsonl", trace.size());
  for (const TraceRay& tr : trace) {
    INFO("ray " << tr.id);
    const nlohmann::json& e = embree[static_cast<std::size_t>(tr.id)];
    REQUIRE(tr.has_reference);
    if (e.contains("occluded")) {
      CHECK((tr.reference_prim == kReferenceOccluded) == e["occluded"].get<bool>());
    } else {
      CHECK(tr.reference_prim == e["prim"].get<int32_t>());
      if (tr.reference_prim >= 0) CHECK(tr.reference_t == e["t"].get<float>());
    }
  }
  // check counts how often the renderer's answer is the exact one; compare-reference takes the trace as reference.
  const std::string scored = (out / "scored.jsonl").string();
  REQUIRE(run_vbsim("oracle -q " + (out / "trace.jsonl").string() + " -o " + scored).exit_code == 0);
  r = run_vbsim("check " + scored);
  INFO(r.output);
  CHECK_THAT(r.output, Catch::Contains(fmt::format("{} rays carry the answer of Embree", trace.size())) &&
                           Catch::Contains(fmt::format("of the {} with an exact answer agree", trace.size())));
  r = run_vbsim("compare-reference " + hits.string() + " " + scored + " -o " + (out / "d.jsonl").string());
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains(fmt::format("{} differ", differing)));
}

TEST_CASE("capture carries ray masks into the trace and the replay honours them", "[cli][capture]") {
  // testbench/capture/embree_masks_app.cpp: an upper square above a ground
  // square, hidden by masks from some of the rays (masks 0x1, 0x3, 0x6 in turn).
  const auto app = std::filesystem::path(VBSIM_CAPTURE_TEST_APP).parent_path() / "vbsim_capture_masks_app";
  // mode, the upper square's mask as the trace holds it, the masks of the rays Embree hid it from
  struct Case {
    const char* mode;
    uint32_t held;
    std::vector<unsigned> hidden_from;
    std::vector<unsigned> marked;  // rays whose masks the trace cannot hold
  };
  const Case c = GENERATE(Case{"geometry", 0x2u, {0x1u}, {}}, Case{"instance", 0x2u, {0x1u}, {}},
                          Case{"both", 0x2u, {0x1u, 0x3u}, {0x3u}});
  INFO("mode " << c.mode);
  const auto dir = scratch_dir(std::string("capture_masks_") + c.mode);
  const auto out = dir / "cap";
  const std::string app_run = app.string() + " " + (dir / "app.txt").string() + " " + c.mode;
  RunResult r = run_vbsim("capture -o " + out.string() + " -- " + app_run);
  INFO(r.output);
  CHECK(r.exit_code == (c.marked.empty() ? 0 : 1));  // marked rays need --allow-partial
  if (!c.marked.empty()) REQUIRE(run_vbsim("capture --allow-partial -o " + out.string() + " -- " + app_run).exit_code == 0);
  std::vector<std::pair<unsigned, unsigned>> app_rays;  // (ray mask, Embree's geomID)
  std::istringstream in(read_file(dir / "app.txt"));
  for (std::string word; in >> word;) {
    unsigned mask = 0, geom = 0;
    in >> mask >> geom;
    app_rays.emplace_back(mask, geom);
  }
  auto file = open_trace((out / "trace.jsonl").string());
  REQUIRE(file->header().triangle_masks);
  const std::vector<TriangleMaskRange>& ranges = *file->header().triangle_masks;
  // The ground is triangles 0-1 (all bits), the upper square 2-3.
  REQUIRE(ranges.size() == 1);
  CHECK(ranges[0].first == 2);
  CHECK(ranges[0].count == 2);
  CHECK(ranges[0].mask == c.held);
  const std::vector<TraceRay> trace = read_trace(out / "trace.jsonl");
  REQUIRE(trace.size() == app_rays.size());
  REQUIRE(trace.size() == 64);
  auto among = [](unsigned m, const std::vector<unsigned>& v) { return std::find(v.begin(), v.end(), m) != v.end(); };
  for (std::size_t i = 0; i < trace.size(); ++i) {
    INFO("ray " << i << " mask " << app_rays[i].first);
    CHECK(trace[i].mask == app_rays[i].first);
    CHECK(app_rays[i].second == (among(app_rays[i].first, c.hidden_from) ? 0u : 1u));  // 0: the ground
    CHECK(trace[i].incomplete == (among(app_rays[i].first, c.marked) ? kIncompleteMask : 0u));
  }
  // The replay reproduces Embree's answer on every unmarked ray, the hidden
  // square's candidates rejected by the mask.
  const auto hits = out / "replay.hits";
  const auto stats = out / "stats.json";
  REQUIRE(run_vbsim("replay -q " + (out / "trace.jsonl").string() + " --hits " + hits.string() + " --stats " +
                    stats.string()).exit_code == 0);
  CHECK(nlohmann::json::parse(read_file(stats))["avoidance"]["rejected_by"]["mask"].get<int>() > 0);
  r = run_vbsim("compare-reference -q " + hits.string() + " " + (out / "embree_hits.jsonl").string());
  std::istringstream diffs(r.output);
  int differing = 0;
  for (std::string line; std::getline(diffs, line);) {
    const auto j = nlohmann::json::parse(line);
    CHECK(trace.at(j["id"].get<std::size_t>()).incomplete == kIncompleteMask);
    ++differing;
  }
  CHECK(differing == static_cast<int>(std::count_if(trace.begin(), trace.end(),
                                                     [](const TraceRay& t) { return t.incomplete != 0; })));
  // The exact answers honour the masks as well: the cycle-level replay, scored, finds no error.
  const auto scored = out / "scored.jsonl";
  REQUIRE(run_vbsim("oracle -q " + (out / "trace.jsonl").string() + " -o " + scored.string()).exit_code == 0);
  REQUIRE(run_vbsim("replay -q --mode cycle " + scored.string() + " --stats " + stats.string()).exit_code == 0);
  const auto j = nlohmann::json::parse(read_file(stats));
  CHECK(j["verdicts"]["correct"].get<int>() == 64 - differing);
}
