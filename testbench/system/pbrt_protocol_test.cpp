// pbrt-v4's Triangle Reintersect protocol: the generator setting
// `protocol=pbrt-v4` and the streamed `vbsim reintersect`, checked against each
// other, against the oracle, and against pbrt-v4's published zero at its size.
#include <catch2/catch.hpp>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "run_vbsim.h"
#include "trace/trace_file.h"
#include "trace/trace_source.h"

using namespace vbsim::test;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path generate_pbrt_v4(const std::string& name, int triangles, int children) {
  const fs::path dir = scratch_dir(name);
  const RunResult r = run_vbsim("gen random-triangles --rays " + std::to_string(triangles) +
                                " --set protocol=pbrt-v4 --set children=" + std::to_string(children) + " -o " +
                                dir.string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return dir;
}

const json& row_of(const json& score, const std::string& method, const std::string& tester, const std::string& kind) {
  for (const json& r : score["rows"])
    if (r["method"] == method && r["tester"] == tester && r["kind"] == kind) return r;
  FAIL("no row " << method << " " << tester << " " << kind);
  throw std::logic_error("unreachable");
}

}  // namespace

TEST_CASE("protocol=pbrt-v4 writes pbrt's trials: positive coordinates, skipped triangles without children, "
          "every child's exact answer a miss",
          "[system][pbrt]") {
  const fs::path dir = generate_pbrt_v4("pbrt_v4_gen", 60, 5);
  int traces = 0, with_children = 0, children = 0;
  std::string description;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".jsonl") continue;
    ++traces;
    auto source = vbsim::open_trace(e.path().string());
    description = source->header().description;
    vbsim::TraceRay tr;
    int rays = 0;
    while (source->next(tr)) {
      ++rays;
      if (tr.kind == vbsim::RayKind::Primary) {
        CHECK(tr.expect_prim == 0);  // the camera ray aims at a point of the triangle
        for (int i = 0; i < 3; ++i) CHECK(tr.o[i] > 0.0f);
        continue;
      }
      ++children;
      CHECK(tr.expect_prim == -1);  // the triangle is the only geometry: a child never meets it
      CHECK(tr.parent == 0);
      CHECK(tr.tmax == (tr.kind == vbsim::RayKind::Shadow ? 1.0f : INFINITY));
    }
    CHECK((rays == 1 || rays == 11));  // camera ray, plus 5 SpawnRay and 5 SpawnRayTo children when it hit
    with_children += rays == 11;
  }
  // Trial RNG(i) for i < 60: none degenerate, the skipped ones keep their camera ray.
  CHECK(traces == 60);
  CHECK(children == 10 * with_children);
  CHECK_THAT(description, Catch::Contains("of the 60 triangles from RNG(0), 0 were dropped as degenerate and " +
                                          std::to_string(60 - with_children) + " skipped"));
}

TEST_CASE("vbsim reintersect counts what gen + score count on the same trials", "[system][pbrt]") {
  const fs::path dir = generate_pbrt_v4("pbrt_v4_score", 40, 20);
  const fs::path out = dir / "score.json.out", rj = dir / "reintersect.json.out";
  const std::string methods = "none,offset-errbound,offset-adaptive";
  const std::string testers = "pbrt-watertight,three-half-plane";
  RunResult r = run_vbsim("score " + dir.string() + " -q --methods " + methods + " --testers " + testers +
                          " --out " + out.string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  r = run_vbsim("reintersect -q --triangles 40 --children 20 --methods " + methods + " --testers " + testers +
                " --json " + rj.string());
  REQUIRE(r.exit_code == 0);
  const json score = json::parse(read_file(out)), re = json::parse(read_file(rj));
  CHECK(re["degenerate"] == 0);
  int64_t rehits = 0;
  for (const json& row : re["rows"]) {
    const std::string m = row["method"], t = row["tester"];
    INFO(m << " " << t);
    CHECK(row["spawn_ray"]["count"] == row_of(score, m, t, "diffuse")["counts"]["self_hit"]);
    CHECK(row["spawn_ray_to"]["count"] == row_of(score, m, t, "shadow")["counts"]["self_hit"]);
    CHECK(row["camera_misses"]["count"] == row_of(score, m, t, "primary")["counts"]["missed"]);
    CHECK(row["spawn_ray"]["of"] == row_of(score, m, t, "diffuse")["rays"]);
    rehits += row["children"]["count"].get<int64_t>();
  }
  CHECK(rehits > 0);  // the comparison is not all zeros: `none` re-hits
  // pbrt's own pair: its offset with its tester re-hits nothing here.
  CHECK(row_of(score, "offset-errbound", "pbrt-watertight", "secondary")["errors"]["count"] == 0);
}

// pbrt-v4's test at its own size (1000 triangles, 1000 + 1000 children each):
// pbrt reports no re-intersection. 49 camera rays are missed by pbrt's test (its
// `continue`), none of the triangles is degenerate.
TEST_CASE("pbrt-v4's Reintersect at pbrt's size: no re-hit of 1,902,000 children", "[system][pbrt]") {
  const fs::path dir = scratch_dir("pbrt_v4_size");
  const fs::path rj = dir / "r.json";
  const RunResult r = run_vbsim("reintersect -q --triangles 1000 --methods offset-errbound --testers "
                                "pbrt-watertight --json " + rj.string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const json re = json::parse(read_file(rj));
  CHECK(re["degenerate"] == 0);
  CHECK(re["skipped"] == 49);
  const json& row = re["rows"][0];
  CHECK(row["children"]["of"] == 1902000);
  CHECK(row["children"]["count"] == 0);
  CHECK(row["children"]["upper"].get<double>() == Approx(2.02).epsilon(0.01));  // 3.84 / 1902000 per million
}

TEST_CASE("vbsim reintersect rejects bad options", "[system][pbrt][errors]") {
  CHECK_THAT(run_vbsim("reintersect --triangles 0").output, Catch::Contains("'--triangles': must be >= 1"));
  CHECK_THAT(run_vbsim("reintersect --testers slab").output, Catch::Contains("unknown tester 'slab'"));
  CHECK_THAT(run_vbsim("reintersect --methods bogus").output, Catch::Contains("method entry 'bogus'"));
  CHECK(run_vbsim("reintersect --exp 99").exit_code != 0);
}
