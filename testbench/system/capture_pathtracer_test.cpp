// vbsim capture on a real path tracer: Debian's embree-tools `pathtracer`
// (installed by scripts/setup.sh) rendering the bundled bunny, 64x48, 1 spp.
// The capture is held against what the renderer must have done (one camera
// ray per pixel from the camera position), every parent link is checked
// against the parent ray's own hit, the image must not change by a byte, and
// the trace goes through oracle, replay in both modes and score.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "datapath/hit_point.h"
#include "capture_test_support.h"
#include "scene/scene.h"
#include "trace/text_trace_reader.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

/// The command line with a camera that frames the bunny; `extra` adds lights.
std::string pathtracer(const std::filesystem::path& image, int threads, const std::string& extra = "") {
  return "pathtracer -i " + source_dir() + "/traces/bunny/bunny.obj --size 64 48 --spp 1 --ambientlight 1 1 1 " +
         extra + " -o " + image.string() + " --threads " + std::to_string(threads) +
         " --vp 0 5 25 --vi 0 4.8 0 --fov 30";
}

int shell(const std::string& cmd) {
  const int status = std::system((cmd + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

float max_abs(Vec3f v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

}  // namespace

TEST_CASE("capture of embree-tools' pathtracer: counts, links, an unchanged image, and the whole pipeline",
          "[cli][capture][pathtracer]") {
  INFO("embree-tools (pathtracer) is installed by scripts/setup.sh");
  REQUIRE(shell("command -v pathtracer") == 0);
  const auto dir = scratch_dir("capture_pathtracer");
  const auto out = dir / "cap";
  REQUIRE(shell(pathtracer(dir / "plain.ppm", 1)) == 0);
  RunResult r = run_vbsim("capture -o " + out.string() + " -- " + pathtracer(out / "image.ppm", 1));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(read_file(out / "image.ppm") == read_file(dir / "plain.ppm"));

  const nlohmann::json report = nlohmann::json::parse(read_file(out / "capture.json"));
  const std::vector<TraceRay> trace = read_trace(out / "trace.jsonl");
  const int64_t intersects = report["calls"]["rtcIntersect1"], occludes = report["calls"]["rtcOccluded1"];
  CHECK(report["calls"].size() == 2);  // the tutorial traces single rays only
  CHECK(static_cast<int64_t>(trace.size()) == intersects + occludes);
  CHECK(report["rays_in_trace"] == trace.size());
  CHECK(report["incomplete"]["rays"] == 0);  // triangles only, no filter functions
  CHECK_THAT(r.output, Catch::Contains("incomplete: 0 rays"));
  // One camera ray per pixel: from the camera position, unlinked, primary.
  int64_t cameras = 0, shadows = 0, children = 0;
  for (const TraceRay& tr : trace) {
    const bool camera = tr.o == Vec3f{0, 5, 25};
    cameras += camera;
    shadows += tr.kind == RayKind::Shadow;
    if (camera) CHECK((tr.parent == -1 && tr.kind == RayKind::Primary));
    children += tr.parent >= 0;
  }
  CHECK(cameras == 64 * 48);
  CHECK(report["links"]["unlinked_intersect"] == cameras);
  CHECK(report["links"]["unlinked_occluded"] == 0);
  CHECK(shadows == occludes);
  CHECK(children == static_cast<int64_t>(trace.size()) - cameras);
  CHECK(children > 1000);

  // Every link points to a hit of the parent ray at the child's origin: the
  // parent's hit (embree_hits) is the child's parent_prim at parent_t, and the
  // child starts at that point, or off it along the triangle's normal by at
  // most 2^-10 of the point's size (the tutorial offsets bounce rays by
  // 32 x 2^-23 x max(|P|, t) along Ng).
  const std::vector<nlohmann::json> hits = read_embree_hits(out / "embree_hits.jsonl", trace.size());
  const Scene scene = load_scene((out / "scene.ply").string());
  CHECK(scene.size() == 3674);
  int at_point = 0;
  for (const TraceRay& c : trace) {
    if (c.parent < 0) continue;
    INFO("ray " << c.id << " parent " << c.parent);
    REQUIRE(c.parent < c.id);
    const TraceRay& p = trace[static_cast<std::size_t>(c.parent)];
    const nlohmann::json& h = hits[static_cast<std::size_t>(p.id)];
    REQUIRE(h["prim"] == c.parent_prim);
    CHECK(h["t"].get<float>() == c.parent_t);
    const Vec3f hit = hit_point_ray(p.o, p.d, c.parent_t);
    const Vec3f off = c.o - hit;
    const Vec3f n = normalize(geometric_normal(scene.triangles[static_cast<std::size_t>(c.parent_prim)]));
    const Vec3f across = off - dot(off, n) * n;
    const float size = std::max(max_abs(hit), max_abs(c.parent_t * p.d));
    CHECK(max_abs(across) <= 8 * 2.4e-7f * size);
    CHECK(std::fabs(dot(off, n)) <= size / 1024);
    at_point += off == Vec3f{};
    CHECK(c.sign == (dot(c.d, geometric_normal(scene.triangles[static_cast<std::size_t>(c.parent_prim)])) < 0 ? 1 : 0));
  }
  CHECK(at_point == shadows);  // shadow rays start at the hit point itself

  // oracle, replay in both modes (the same hits), score.
  std::filesystem::create_directories(out / "scored");  // a family of its own for score
  const std::string scored = (out / "scored" / "trace.jsonl").string();
  REQUIRE(run_vbsim("oracle " + out.string() + "/trace.jsonl -o " + scored).exit_code == 0);
  r = run_vbsim("check --strict " + scored);
  CHECK(r.exit_code == 0);
  for (const char* mode : {"functional", "cycle"}) {
    r = run_vbsim(std::string("replay -q ") + scored + " --mode " + mode + " --method validity-bit --stats " +
                  (out / (std::string(mode) + ".json")).string() + " --hits " + (out / (std::string(mode) + ".hits")).string());
    INFO(mode << ": " << r.output);
    REQUIRE(r.exit_code == 0);
    const auto stats = nlohmann::json::parse(read_file(out / (std::string(mode) + ".json")));
    CHECK(stats["rays"] == trace.size());
    CHECK(stats["verdicts"]["unscored"] == 0);
  }
  CHECK(without_provenance(read_file(out / "functional.hits")) == without_provenance(read_file(out / "cycle.hits")));
  r = run_vbsim("score " + (out / "scored").string() + " --methods none,validity-bit --threads 2 --out " + (out / "score.json").string());
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("validity-bit"));
}

TEST_CASE("capture of a lit, two-threaded pathtracer render: the same image and the one-thread trace",
          "[cli][capture][pathtracer]") {
  REQUIRE(shell("command -v pathtracer") == 0);
  const auto dir = scratch_dir("capture_pathtracer_threads");
  const std::string lights = "--pointlight 10 20 20 300 300 300";
  // Dimmer ambient light than the so that the image is not saturated white.
  auto command = [&](const std::filesystem::path& image, int threads) {
    std::string c = pathtracer(image, threads, lights);
    c.replace(c.find("--ambientlight 1 1 1"), 20, "--ambientlight 0.3 0.3 0.3");
    return c;
  };
  REQUIRE(shell(command(dir / "plain.ppm", 2)) == 0);
  // A small render may finish before the renderer's second thread takes a
  // tile: the two-thread capture is repeated until both traced (each run takes
  // a fraction of a second; on a loaded machine it can take tens of tries).
  auto capture = [&](int threads) {
    const auto out = dir / ("t" + std::to_string(threads));
    const RunResult r =
        run_vbsim("capture --strip-offsets -o " + out.string() + " -- " + command(out / "image.ppm", threads));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(read_file(out / "image.ppm") == read_file(dir / "plain.ppm"));
    return nlohmann::json::parse(read_file(out / "capture.json"));
  };
  capture(1);
  nlohmann::json report = capture(2);
  for (int attempt = 1; attempt < 40 && report["threads"] < 2; ++attempt) report = capture(2);
  REQUIRE(report["threads"] >= 2);
  CHECK(trace_rays_text(dir / "t1" / "trace.jsonl") == trace_rays_text(dir / "t2" / "trace.jsonl"));
  // --strip-offsets: every child starts at its parent's hit point with tmin 0.
  // That point is the application's (its origin + t d): for a child of a
  // camera ray it is the trace's parent ray at parent_t exactly; deeper, the
  // parent's own origin was moved back onto its surface, so the two differ by
  // that removed offset.
  const std::vector<TraceRay> trace = read_trace(dir / "t2" / "trace.jsonl");
  int64_t children = 0;
  for (const TraceRay& c : trace) {
    if (c.parent < 0) continue;
    ++children;
    const TraceRay& p = trace[static_cast<std::size_t>(c.parent)];
    const Vec3f hit = hit_point_ray(p.o, p.d, c.parent_t);
    if (p.parent < 0) CHECK(c.o == hit);
    else CHECK(max_abs(c.o - hit) <= std::max(max_abs(hit), max_abs(c.parent_t * p.d)) / 1024);
    CHECK(c.tmin == 0.0f);
  }
  CHECK(children == report["links"]["at_hit_point"].get<int64_t>() + report["links"]["normal_offset"].get<int64_t>());
  CHECK(report["strip_offsets"]["tmin_cleared"] == children);
}
