// vbsim bench over a captured trace (--trace, text or binary, its scene from
// the header), its disagreement counts, and its refusals of bad input.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

const std::string kTrace = source_dir() + "/traces/bunny/paths.jsonl";

nlohmann::json bench_json(const std::string& args, const std::filesystem::path& out) {
  const RunResult r = run_vbsim("bench " + args + " --repeats 1 --json " + out.string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return nlohmann::json::parse(read_file(out));
}

int64_t classified(const nlohmann::json& d) {
  return d["tie"].get<int64_t>() + d["embree_wrong"].get<int64_t>() + d["vbsim_wrong"].get<int64_t>() +
         d["both_wrong"].get<int64_t>() + d["method"].get<int64_t>();
}

}  // namespace

TEST_CASE("bench --trace times the bundled trace's rays over its scene, every disagreement classified",
          "[cli][bench]") {
  const auto dir = scratch_dir("bench_trace");
  const nlohmann::json j = bench_json("--trace " + kTrace, dir / "f.json");
  CHECK(j["workload"] == "trace");
  CHECK(j["trace"] == kTrace);
  CHECK(j["rays"] == 1008);  // every ray of the trace
  CHECK(j["triangles"] == 3674);
  CHECK(j["seed"].is_null());
  CHECK(j["vbsim_rays_per_s"].get<double>() > 0);
  CHECK(j["embree_rays_per_s"].get<double>() > 0);
  // Each ray agrees or is classified. With method none a child starts on its
  // parent triangle, where the sign of a float t decides a self-hit: every
  // answer vbsim gets wrong here is on that triangle (rays 218 and 619 when
  // Embree answers them right), none elsewhere.
  const nlohmann::json& d = j["disagreements"];
  CHECK(j["same_prim"].get<int64_t>() + classified(d) == 1008);
  CHECK(d["vbsim_wrong"] == d["at_parent"]["vbsim_wrong"]);
  CHECK(d["both_wrong"] == 0);
  CHECK(d["rays"].size() == static_cast<size_t>(classified(d)));
  for (const nlohmann::json& ray : d["rays"])
    if (ray["class"] == "vbsim_wrong") {
      CHECK(ray["at_parent"] == true);
      CHECK((ray["id"] == 218 || ray["id"] == 619));
    }

  // The first N rays, and the printed summary.
  const RunResult r = run_vbsim("bench --trace " + kTrace + " --rays 100 --repeats 1");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("100 rays of " + kTrace) && Catch::Contains("3674 triangles") &&
                           Catch::Contains("shadow rays: occluded alike"));

  // The cycle-level model on the same rays gives the same answers.
  const nlohmann::json c = bench_json("--trace " + kTrace + " --mode cycle", dir / "c.json");
  CHECK(c["rays"] == 1008);
  CHECK(c["hw"]["cycles"].get<uint64_t>() > 0);
  CHECK(c["same_prim"] == j["same_prim"]);
  CHECK(c["disagreements"] == d);
  std::filesystem::remove_all(dir);
}

TEST_CASE("bench --trace reads the binary form alike", "[cli][bench]") {
  const auto dir = scratch_dir("bench_trace_vbt");
  const auto vbt = dir / "paths.vbt";
  const RunResult conv = run_vbsim("convert " + kTrace + " -o " + vbt.string());
  REQUIRE(conv.exit_code == 0);
  const nlohmann::json text = bench_json("--trace " + kTrace, dir / "t.json");
  const nlohmann::json binary = bench_json("--trace " + vbt.string(), dir / "b.json");
  CHECK(binary["rays"] == text["rays"]);
  CHECK(binary["vbsim_hits"] == text["vbsim_hits"]);
  CHECK(binary["same_prim"] == text["same_prim"]);
  CHECK(binary["disagreements"] == text["disagreements"]);
  std::filesystem::remove_all(dir);
}

TEST_CASE("bench --trace refuses a missing trace, a bad scene and options for random rays", "[cli][bench]") {
  const auto dir = scratch_dir("bench_trace_bad");
  RunResult r = run_vbsim("bench --trace " + (dir / "nonesuch.jsonl").string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains((dir / "nonesuch.jsonl").string()));

  const auto no_scene = dir / "no_scene.jsonl";
  write_file(no_scene, "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"missing.obj\"}\n"
                       "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n");
  r = run_vbsim("bench --trace " + no_scene.string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains(no_scene.string() + ": header: field 'scene'") &&
                           Catch::Contains("missing.obj"));

  const auto bad_prim = dir / "bad_prim.jsonl";
  write_file(bad_prim, "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"" + source_dir() +
                           "/traces/bunny/bunny.obj\"}\n"
                           "{\"id\":0,\"o\":[0,0,5],\"d\":[0,0,-1]}\n"
                           "{\"id\":1,\"parent\":0,\"kind\":\"reflect\",\"o\":[0,0,0],\"d\":[0,0,-1],\"parent_prim\":999999}\n");
  r = run_vbsim("bench --trace " + bad_prim.string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains(bad_prim.string() + ":3") && Catch::Contains("parent_prim"));

  r = run_vbsim("bench --trace " + kTrace + " --scene " + source_dir() + "/traces/bunny/bunny.obj");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("'--trace' and '--scene'"));
  r = run_vbsim("bench --trace " + kTrace + " --seed 3");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("'--seed'"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("bench --threads times both sides again on several threads, answers as on one thread", "[cli][bench]") {
  const auto dir = scratch_dir("bench_threads");
  // Children start at their parent's ray-equation hit point: each ray replayed
  // on its own needs its parent's trace ray (without it 157 of these rays
  // get another answer).
  const nlohmann::json j = bench_json("--trace " + kTrace + " --hitpoint ray --threads 3", dir / "t.json");
  const nlohmann::json& t = j["threaded"];
  REQUIRE(t.is_object());
  CHECK(t["threads"] == 3);
  CHECK(t["vbsim_differ_from_one_thread"] == 0);
  CHECK(t["embree_differ_from_one_thread"] == 0);
  CHECK(t["vbsim_rays_per_s"].get<double>() > 0);
  CHECK(t["embree_rays_per_s"].get<double>() > 0);
  CHECK(bench_json("--trace " + kTrace + " --threads 1", dir / "one.json")["threaded"].is_null());
  CHECK(bench_json("--trace " + kTrace + " --mode cycle --rays 50", dir / "c.json")["threaded"].is_null());
  const RunResult bad = run_vbsim("bench --threads 0 --rays 10");
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.output, Catch::Contains("--threads"));
  const RunResult cycle = run_vbsim("bench --mode cycle --threads 2 --rays 10");
  CHECK(cycle.exit_code == 2);
  CHECK_THAT(cycle.output, Catch::Contains("functional mode only"));
}
