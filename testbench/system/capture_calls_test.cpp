// vbsim capture on testbench/capture/embree_calls_app.cpp, which keeps its own
// account of every ray it traced (entry point, inputs, Embree's answer, the
// parent and kind it meant): the capture must agree with that account ray for
// ray, number the scene's triangles as documented, and be the same whatever
// the number of threads; the application's output must not change.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "capture_test_support.h"
#include "scene/scene.h"
#include "trace/text_trace_reader.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

struct AppRay {
  bool occluded;
  std::string api;
  float o[3], d[3], tnear, tfar;
  int geom, prim;
  float t, u, v, ng[3];
  int parent;  // index within its item, -1 for none
  std::string kind;
  int item;
  int index;  // within the item
};

struct AppRecord {
  std::map<std::string, int64_t> calls;
  std::vector<AppRay> rays;
};

AppRecord read_app_record(const std::filesystem::path& p) {
  AppRecord rec;
  std::istringstream in(read_file(p));
  std::string word;
  int item = -1, index = 0;
  while (in >> word) {
    if (word == "calls") {
      std::string name;
      int64_t n;
      in >> name >> n;
      rec.calls[name] = n;
    } else if (word == "item") {
      in >> item;
      index = 0;
    } else if (word == "ray") {
      AppRay r;
      std::string op, f[8], skip, h[6];
      in >> op >> r.api;
      for (auto& s : f) in >> s;
      in >> skip >> r.geom >> r.prim;
      for (auto& s : h) in >> s;
      in >> skip >> r.parent >> r.kind;
      r.occluded = op == "O";
      float* dst[8] = {&r.o[0], &r.o[1], &r.o[2], &r.d[0], &r.d[1], &r.d[2], &r.tnear, &r.tfar};
      for (int k = 0; k < 8; ++k) *dst[k] = std::strtof(f[k].c_str(), nullptr);  // hex floats, exact
      float* hit[6] = {&r.t, &r.u, &r.v, &r.ng[0], &r.ng[1], &r.ng[2]};
      for (int k = 0; k < 6; ++k) *hit[k] = std::strtof(h[k].c_str(), nullptr);
      r.item = item;
      r.index = index++;
      rec.rays.push_back(r);
    }
  }
  return rec;
}

std::string bits_key(bool occluded, const float* o, const float* d, float tnear, float tfar) {
  std::string k(1, occluded ? 'O' : 'I');
  const float v[8] = {o[0], o[1], o[2], d[0], d[1], d[2], tnear, tfar};
  k.append(reinterpret_cast<const char*>(v), sizeof v);
  return k;
}

/// The documented numbering for the app's scene: captured triangle and quad
/// geometries by ascending geomID (0: floor, 2 triangles; 1: slanted, 1; 2:
/// one quad, split as Embree splits it into (v0, v1, v3), where u + v <= 1,
/// and (v2, v3, v1); 7: wall, 2).
int expected_triangle(int geom, int prim, float u, float v) {
  if (geom == 0) return prim;
  if (geom == 1) return 2 + prim;
  if (geom == 2) return 3 + 2 * prim + (u + v <= 1.0f ? 0 : 1);
  if (geom == 7) return 5 + prim;
  return -1;
}

}  // namespace

TEST_CASE("capture agrees ray for ray with an application's own account of its Embree calls", "[cli][capture]") {
  const auto dir = scratch_dir("capture_calls");
  const std::string app = VBSIM_CAPTURE_TEST_APP;
  REQUIRE(std::system((app + " 1 " + (dir / "plain.txt").string()).c_str()) == 0);
  for (const char* threads : {"1", "4"}) {
    const auto out = dir / (std::string("t") + threads);
    const RunResult r = run_vbsim("capture --allow-partial -o " + out.string() + " -- " + app + " " + threads + " " +
                                  (out / "app.txt").string());
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(read_file(out / "app.txt") == read_file(dir / "plain.txt"));  // the capture changes nothing
    CHECK_FALSE(std::filesystem::exists(out / "raw"));
  }
  // Any number of threads: the same trace, scene and answers.
  CHECK(nlohmann::json::parse(read_file(dir / "t4" / "capture.json"))["threads"] == 4);
  CHECK(trace_rays_text(dir / "t1" / "trace.jsonl") == trace_rays_text(dir / "t4" / "trace.jsonl"));
  // The same scene but for the provenance comment (which names the command line).
  CHECK(without_provenance(read_file(dir / "t1" / "scene.ply")) == without_provenance(read_file(dir / "t4" / "scene.ply")));
  CHECK_THAT(read_file(dir / "t1" / "scene.ply"), Catch::Contains("\ncomment vbsim-provenance {"));
  CHECK_THAT(read_file(dir / "t1" / "trace.jsonl").substr(0, read_file(dir / "t1" / "trace.jsonl").find('\n')),
             Catch::Contains("\"provenance\":{"));
  CHECK(read_file(dir / "t1" / "embree_hits.jsonl") == read_file(dir / "t4" / "embree_hits.jsonl"));

  const AppRecord app_rec = read_app_record(dir / "plain.txt");
  const auto out = dir / "t1";
  const nlohmann::json report = nlohmann::json::parse(read_file(out / "capture.json"));
  for (const auto& [name, n] : app_rec.calls) CHECK(report["calls"][name] == n);
  CHECK(report["calls"].size() == app_rec.calls.size());
  CHECK(report["rays_in_trace"] == app_rec.rays.size());
  CHECK(report["not_captured"]["invalid"] == 0);

  const std::vector<TraceRay> trace = read_trace(out / "trace.jsonl");
  REQUIRE(trace.size() == app_rec.rays.size());
  std::map<std::string, int64_t> id_of;
  for (const TraceRay& tr : trace) {
    const float o[3] = {tr.o.x, tr.o.y, tr.o.z}, d[3] = {tr.d.x, tr.d.y, tr.d.z};
    CHECK(id_of.emplace(bits_key(tr.kind == RayKind::Shadow, o, d, tr.tmin, tr.tmax), tr.id).second);
  }
  const std::vector<nlohmann::json> hits = read_embree_hits(out / "embree_hits.jsonl", trace.size());
  const Scene scene = load_scene((out / "scene.ply").string());
  REQUIRE(scene.size() == 7);
  CHECK(scene.triangles[0].v1 == Vec3f{10, -10, 0});  // floor, from a 16-byte-stride shared buffer
  CHECK(scene.triangles[2].v2 == Vec3f{0, 3, 6});     // slanted, from a new buffer
  CHECK(scene.triangles[6].v2 == Vec3f{8, -10, 10});  // wall, geomID 7, from an RTCBuffer at offset 16

  int outside = 0, linked = 0, quad_hits = 0;
  std::map<std::pair<int, int>, int64_t> item_ids;  // (item, index) -> trace id
  for (const AppRay& a : app_rec.rays) {
    INFO("item " << a.item << " ray " << a.index << " " << a.kind);
    const auto it = id_of.find(bits_key(a.occluded, a.o, a.d, a.tnear, a.tfar));
    REQUIRE(it != id_of.end());
    const TraceRay& tr = trace[static_cast<std::size_t>(it->second)];
    item_ids[{a.item, a.index}] = tr.id;
    CHECK(ray_kind_name(tr.kind) == a.kind);
    const nlohmann::json& h = hits[static_cast<std::size_t>(tr.id)];
    if (a.occluded) {
      CHECK(h["occluded"] == (std::isinf(a.t) && a.t < 0));
    } else if (a.geom < 0) {
      CHECK(h["prim"] == -1);
    } else {
      CHECK(h["prim"] == expected_triangle(a.geom, a.prim, a.u, a.v));
      CHECK(h["geom"] == a.geom);
      CHECK(h["t"].get<float>() == a.t);
      outside += expected_triangle(a.geom, a.prim, a.u, a.v) < 0;
      quad_hits += a.geom == 2;
      if (expected_triangle(a.geom, a.prim, a.u, a.v) >= 0) {
        // Embree's geometric normal points the way the trace format's (v1 - v0) x (v2 - v0) does.
        const Triangle& tri = scene.triangles[static_cast<std::size_t>(expected_triangle(a.geom, a.prim, a.u, a.v))];
        CHECK(dot(geometric_normal(tri), Vec3f{a.ng[0], a.ng[1], a.ng[2]}) > 0.0f);
      }
    }
    if (a.parent < 0) {
      CHECK(tr.parent == -1);
      continue;
    }
    ++linked;
    const AppRay& p = app_rec.rays[&a - app_rec.rays.data() - (a.index - a.parent)];
    REQUIRE(p.index == a.parent);
    CHECK(tr.parent == item_ids.at({a.item, a.parent}));
    CHECK(tr.parent_prim == expected_triangle(p.geom, p.prim, p.u, p.v));
    CHECK(tr.parent_t == p.t);
    CHECK(tr.parent_u == p.u);
    CHECK(tr.parent_v == p.v);
    CHECK(tr.sign == (dot(tr.d, geometric_normal(scene.triangles[static_cast<std::size_t>(tr.parent_prim)])) < 0.0f ? 1 : 0));
  }
  CHECK(linked == report["links"]["at_hit_point"].get<int>() + report["links"]["normal_offset"].get<int>());
  CHECK(linked > 200);
  CHECK(outside == 0);  // the quad mesh is captured too
  CHECK(quad_hits == 1);
  CHECK(report["hits_outside_captured_triangles"] == outside);
  // Every geometry that takes part is captured: no ray is marked.
  CHECK(report["incomplete"]["rays"] == 0);
  int64_t marked = 0;
  for (const TraceRay& tr : trace) marked += tr.incomplete != 0;
  CHECK(marked == 0);
  const auto& geoms = report["scene"]["geometries"];
  REQUIRE(geoms.size() == 5);
  CHECK(geoms[2]["status"] == "captured");
  CHECK(geoms[2]["type"] == "quad");
  CHECK(geoms[2]["triangles"] == 2);
  CHECK(geoms[3]["status"] == "disabled");
  CHECK(geoms[4]["geomID"] == 7);
  CHECK(geoms[4]["first_triangle"] == 5);

  // The trace checks clean but for the missing answers, which the oracle fills in.
  RunResult r = run_vbsim("check " + (out / "trace.jsonl").string());
  CHECK_THAT(r.output, Catch::Contains(" 0 errors") && Catch::Contains("(missing_expect " + std::to_string(trace.size()) + ")"));
  REQUIRE(run_vbsim("oracle " + (out / "trace.jsonl").string() + " -o " + (out / "scored.jsonl").string()).exit_code == 0);
  r = run_vbsim("check --strict " + (out / "scored.jsonl").string());
  INFO(r.output);
  CHECK(r.exit_code == 0);
}

TEST_CASE("capture reports an application that fails or cannot start, and writes no trace", "[cli][capture]") {
  const auto dir = scratch_dir("capture_fail");
  RunResult r = run_vbsim("capture -o " + (dir / "a").string() + " -- sh -c 'exit 3'");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("exited with status 3") && Catch::Contains("no trace written"));
  CHECK_FALSE(std::filesystem::exists(dir / "a" / "trace.jsonl"));
  r = run_vbsim("capture -o " + (dir / "b").string() + " -- /nonexistent/renderer");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("cannot run /nonexistent/renderer"));
  r = run_vbsim("capture -o " + (dir / "c").string() + " -- true");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("no Embree ray queries were captured"));
}
