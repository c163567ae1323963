// vbsim convert --to rtcore: rays vbsim generated go out as rtcore-systemc ray
// files with the scene as a PLY mesh, and come back bit for bit.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"
#include "trace/text_trace_reader.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

std::vector<TraceRay> read_rays(const std::string& path) {
  TextTraceReader reader(path);
  std::vector<TraceRay> rays;
  TraceRay r;
  while (reader.next(r)) rays.push_back(r);
  return rays;
}

uint32_t bits(float x) {
  uint32_t b;
  std::memcpy(&b, &x, 4);
  return b;
}

/// prim of every hit line, by id.
std::map<int64_t, int> hit_prims(const std::filesystem::path& hits) {
  std::map<int64_t, int> out;
  std::istringstream in(read_file(hits));
  std::string line;
  while (std::getline(in, line)) {
    const auto j = nlohmann::json::parse(line);
    if (!j.contains("id")) continue;  // the provenance header line
    out[j["id"].get<int64_t>()] = j["prim"].get<int>();
  }
  return out;
}

}  // namespace

TEST_CASE("convert --to rtcore: a generated trace round-trips o, d and tmax and primary rays hit the same triangles",
          "[cli][rtcore]") {
  const auto dir = scratch_dir("convert_to_rtcore");
  // far-instance carries a header transform: the mesh written must have it applied.
  for (const std::string& scenario : {std::string("paths"), std::string("far-instance")}) {
    INFO(scenario);
    const auto gen = dir / scenario;
    REQUIRE(run_vbsim("gen " + scenario + " --rays 30 -o " + gen.string()).exit_code == 0);
    std::filesystem::path trace;
    for (const auto& e : std::filesystem::directory_iterator(gen))
      if (e.path().extension() == ".jsonl") trace = e.path();
    REQUIRE(!trace.empty());
    const auto rays_bin = gen / "ray_queries.bin", mesh = gen / "mesh.ply", back = gen / "back.jsonl";
    RunResult r = run_vbsim("convert " + trace.string() + " --to rtcore -o " + rays_bin.string() + " --scene-out " +
                            mesh.string());
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const std::vector<TraceRay> original = read_rays(trace.string());
    REQUIRE(std::filesystem::file_size(rays_bin) == 28 * original.size());
    // The mesh says what wrote it, with the trace's and the scene's checksums (README "Provenance").
    const std::string mesh_text = read_file(mesh);
    const std::string comment = mesh_text.substr(mesh_text.find("\ncomment vbsim-provenance {") + 1);
    CHECK_THAT(comment.substr(0, comment.find('\n')), Catch::Contains("\"command\"") && Catch::Contains(trace.filename().string()));
    // Record 0, decoded by hand: little-endian float32 ox oy oz dx dy dz tmax.
    const std::string bytes = read_file(rays_bin);
    float rec[7];
    std::memcpy(rec, bytes.data(), sizeof rec);
    const TraceRay& first = original.front();
    CHECK(bits(rec[0]) == bits(first.o.x));
    CHECK(bits(rec[5]) == bits(first.d.z));
    CHECK(bits(rec[6]) == bits(first.tmax));

    r = run_vbsim("convert " + rays_bin.string() + " --from rtcore --scene " + mesh.string() + " -o " + back.string());
    REQUIRE(r.exit_code == 0);
    const std::vector<TraceRay> returned = read_rays(back.string());
    REQUIRE(returned.size() == original.size());
    for (std::size_t i = 0; i < original.size(); ++i) {
      CHECK(returned[i].id == static_cast<int64_t>(i));
      CHECK(bits(returned[i].o.x) == bits(original[i].o.x));
      CHECK(bits(returned[i].o.y) == bits(original[i].o.y));
      CHECK(bits(returned[i].o.z) == bits(original[i].o.z));
      CHECK(bits(returned[i].d.x) == bits(original[i].d.x));
      CHECK(bits(returned[i].d.y) == bits(original[i].d.y));
      CHECK(bits(returned[i].d.z) == bits(original[i].d.z));
      CHECK(bits(returned[i].tmax) == bits(original[i].tmax));
    }
    // Both traces replayed with no method: a camera ray meets the same triangle
    // of the original scene (transform applied) and of the exported mesh.
    REQUIRE(run_vbsim("replay -q " + trace.string() + " --hits " + (gen / "a.hits").string()).exit_code == 0);
    REQUIRE(run_vbsim("replay -q " + back.string() + " --hits " + (gen / "b.hits").string()).exit_code == 0);
    const auto a = hit_prims(gen / "a.hits"), b = hit_prims(gen / "b.hits");
    int primaries = 0, hits = 0;
    for (std::size_t i = 0; i < original.size(); ++i) {
      if (original[i].kind != RayKind::Primary) continue;
      ++primaries;
      hits += a.at(original[i].id) >= 0;
      CHECK(a.at(original[i].id) == b.at(static_cast<int64_t>(i)));
    }
    CHECK(primaries > 0);
    CHECK(hits > 0);
  }
}

TEST_CASE("convert --to rtcore refuses a ray with tmin and leaves no output", "[cli][rtcore]") {
  const auto dir = scratch_dir("convert_to_rtcore_tmin");
  write_file(dir / "t.jsonl", "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"s.ply\"}\n"
                              "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n{\"id\":1,\"o\":[0,0,5],\"d\":[0,0,-1],\"tmin\":0.5}\n");
  const RunResult r = run_vbsim("convert " + (dir / "t.jsonl").string() + " --to rtcore -o " + (dir / "r.bin").string());
  INFO(r.output);
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("record 1") && Catch::Contains("tmin"));
  CHECK_FALSE(std::filesystem::exists(dir / "r.bin"));
  CHECK(run_vbsim("convert " + (dir / "t.jsonl").string() + " --to bogus -o x").exit_code != 0);
}
