// vbsim render as a user runs it: PNG files that stb_image reads back with the
// documented colours, the printed pixel counts, and clear errors.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <stb/stb_image.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <regex>

#include "../unit/render_test_scene.h"
#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

struct Png {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> data{nullptr, stbi_image_free};
  std::array<int, 3> at(int x, int y) const {
    const unsigned char* p = data.get() + 3 * (size_t(y) * w + x);
    return {p[0], p[1], p[2]};
  }
};

Png read_png(const std::filesystem::path& p) {
  Png png;
  png.data.reset(stbi_load(p.string().c_str(), &png.w, &png.h, &png.channels, 3));
  return png;
}

long printed_count(const std::string& output, const std::string& what) {
  std::smatch m;
  if (!std::regex_search(output, m, std::regex(what + " (\\d+)"))) return -1;
  return std::stol(m[1]);
}

}  // namespace

TEST_CASE("render writes both images readable by stb_image with the legend's colours", "[render][cli]") {
  const auto dir = scratch_dir("render_png");
  write_render_test_obj((dir / "quad.obj").string());
  const RunResult r = run_vbsim("render " + (dir / "quad.obj").string() + " --method none --size 8x6 --light " +
                                kRenderTestLight + " -o " + (dir / "img.png").string() + " --errors " +
                                (dir / "err.png").string());
  REQUIRE(r.exit_code == 0);
  const Png img = read_png(dir / "img.png"), err = read_png(dir / "err.png");
  REQUIRE(img.data);
  REQUIRE(err.data);
  CHECK(img.w == 8);
  CHECK(img.h == 6);
  CHECK(img.channels == 3);
  CHECK(err.w == 8);
  CHECK(err.h == 6);
  // The top-left pixel looks over the scene: the documented background, and
  // its grey level (77 r + 150 g + 29 b) / 256 in the error image.
  CHECK(img.at(0, 0) == std::array<int, 3>{60, 72, 96});
  CHECK(err.at(0, 0) == std::array<int, 3>{71, 71, 71});
  // As many red pixels in the error image as the command reports acne pixels.
  long red = 0;
  for (int y = 0; y < err.h; ++y)
    for (int x = 0; x < err.w; ++x) red += err.at(x, y) == std::array<int, 3>{255, 40, 40};
  CHECK(red > 0);
  CHECK(printed_count(r.output, "acne") == red);
  CHECK(printed_count(r.output, "leak") == 0);
}

TEST_CASE("render takes scene and light and transform from a trace header", "[render][cli]") {
  const auto dir = scratch_dir("render_trace");
  write_render_test_obj((dir / "quad.obj").string());
  // A header-only trace moving the scene 2^12 away in x.
  write_file(dir / "far.jsonl",
             "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"quad.obj\",\"light\":[4096,50,-30],"
             "\"transform\":[1,0,0,4096, 0,1,0,0, 0,0,1,0, 0,0,0,1]}\n");
  const RunResult r = run_vbsim("render " + (dir / "far.jsonl").string() +
                                " -m offset-errbound --size 8x8 -o " + (dir / "far.png").string());
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("light point:4096,50,-30"));
  CHECK(printed_count(r.output, "acne") == 0);
  CHECK(printed_count(r.output, "leak") == 0);
  const Png img = read_png(dir / "far.png");
  REQUIRE(img.data);
  CHECK(img.w == 8);
}

TEST_CASE("render errors name the option or the file", "[render][cli]") {
  const auto dir = scratch_dir("render_errors");
  write_render_test_obj((dir / "quad.obj").string());
  const std::string scene = (dir / "quad.obj").string(), out = " -o " + (dir / "x.png").string();
  for (const char* size : {"8", "0x8", "8x", "8x8x8", "axb", "99999x2"}) {
    INFO(size);
    const RunResult r = run_vbsim("render " + scene + out + " --size " + size);
    CHECK(r.exit_code != 0);
    CHECK(r.exit_code < 128);
    CHECK_THAT(r.output, Catch::Contains("--size") && Catch::Contains(size));
  }
  RunResult r = run_vbsim("render " + (dir / "missing.ply").string() + out);
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("missing.ply"));
  r = run_vbsim("render " + scene + out + " --light sun:1,2,3");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("--light") && Catch::Contains("sun:1,2,3"));
  r = run_vbsim("render " + scene + out + " --camera 1,2,3");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("--camera"));
  r = run_vbsim("render " + scene + " -o " + (dir / "no_such_dir" / "x.png").string());
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("no_such_dir"));
  r = run_vbsim("render " + scene + out + " --ao-radius 0.2");  // the mirror integrator has no occlusion rays
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("--ao-radius") && Catch::Contains("--integrator ao"));
  for (const char* radius : {"0", "-1", "inf"}) {
    r = run_vbsim("render " + scene + out + " --integrator ao --ao-radius " + radius);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Catch::Contains("--ao-radius"));
  }
  r = run_vbsim("render " + scene + out + " --integrator ao --spp 4 --ao-radius 0.05 --stats " +
                (dir / "ao.json").string() + " -q");
  REQUIRE(r.exit_code == 0);
  std::ifstream in(dir / "ao.json");
  const nlohmann::json ao = nlohmann::json::parse(in);
  CHECK(ao["config"]["integrator"] == "ao");
  CHECK(ao["config"]["samples"] == 4);
  CHECK(ao["by_kind"]["shadow"]["rays"].get<uint64_t>() == 4 * ao["by_kind"]["primary"]["hits"].get<uint64_t>());
}

TEST_CASE("render --mode cycle: the frame's hardware figures, and a closed-loop trace that replays to its cycles",
          "[render][cli][closed-loop]") {
  const auto dir = scratch_dir("render_cycle");
  const std::string obj = (dir / "quad.obj").string();
  write_render_test_obj(obj);
  const std::string common = "render " + obj + " --method none --size 12x9 --light " + kRenderTestLight +
                             " --integrator path --spp 2 --bounces 1";
  const RunResult cycle = run_vbsim(common + " --mode cycle -o " + (dir / "c.png").string() + " --stats " +
                                    (dir / "c.json").string() + " --trace-out " + (dir / "c.jsonl").string());
  REQUIRE(cycle.exit_code == 0);
  CHECK(cycle.output.find("render (cycle)") != std::string::npos);
  const RunResult functional = run_vbsim(common + " -o " + (dir / "f.png").string() + " -q");
  REQUIRE(functional.exit_code == 0);
  const Png c = read_png(dir / "c.png"), f = read_png(dir / "f.png");
  REQUIRE(c.data);
  REQUIRE(f.data);
  CHECK(std::equal(c.data.get(), c.data.get() + 12 * 9 * 3, f.data.get()));  // the same image

  std::ifstream stats_in(dir / "c.json");
  const nlohmann::json stats = nlohmann::json::parse(stats_in);
  const uint64_t cycles = stats["hw"]["cycles"].get<uint64_t>();
  CHECK(cycles > 0);
  CHECK(stats["hw"]["energy"]["total_pj"].get<double>() > 0);
  CHECK(stats["config"]["integrator"] == "path");
  CHECK(stats["config"]["children_from"] == "method");
  CHECK(stats["pixels"]["total"] == 108);
  const RunResult replay = run_vbsim("replay " + (dir / "c.jsonl").string() + " --method none --mode cycle --stats " +
                                     (dir / "r.json").string() + " -q");
  REQUIRE(replay.exit_code == 0);
  std::ifstream replay_in(dir / "r.json");
  const nlohmann::json replayed = nlohmann::json::parse(replay_in);
  CHECK(replayed["hw"]["cycles"].get<uint64_t>() == cycles);
  CHECK(replayed["rays"] == stats["rays"]);
  CHECK(replayed["verdicts"] == stats["verdicts"]);  // each ray carries its exact answer
}

TEST_CASE("render --mode cycle refuses dependencies off, naming the config file, and without shader time replays to "
          "its cycles",
          "[render][cli][closed-loop]") {
  // With hw.source.dependencies false a render of the bunny (path integrator,
  // 40x30) gave 18,495 cycles and the replay of its --trace-out 17,447: the
  // render's children always wait for their parents' answers, the replay's did not.
  const auto dir = scratch_dir("render_cycle_deps");
  const std::string obj = (dir / "quad.obj").string();
  write_render_test_obj(obj);
  const std::string common = "render " + obj + " --method none --size 12x9 --light " + kRenderTestLight +
                             " --integrator path --spp 2 --bounces 1 --mode cycle -o " + (dir / "c.png").string();
  write_file(dir / "nodeps.json", R"({"hw":{"source":{"dependencies":false}}})");
  RunResult r = run_vbsim(common + " --config " + (dir / "nodeps.json").string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains((dir / "nodeps.json").string() + ": field 'hw.source.dependencies'") &&
                           Catch::Contains("shader.latency_cycles"));
  CHECK_FALSE(std::filesystem::exists(dir / "c.png"));

  // What it would have meant, no time between an answer and its children, is shader latency 0.
  write_file(dir / "nolatency.json", R"({"hw":{"shader":{"latency_cycles":0}}})");
  const std::string config = " --config " + (dir / "nolatency.json").string();
  r = run_vbsim(common + config + " --stats " + (dir / "c.json").string() + " --trace-out " +
                (dir / "c.jsonl").string() + " -q");
  REQUIRE(r.exit_code == 0);
  r = run_vbsim("replay " + (dir / "c.jsonl").string() + " --method none --mode cycle" + config + " --stats " +
                (dir / "r.json").string() + " -q");
  REQUIRE(r.exit_code == 0);
  const auto rendered = nlohmann::json::parse(read_file(dir / "c.json"));
  const auto replayed = nlohmann::json::parse(read_file(dir / "r.json"));
  CHECK(replayed["hw"]["cycles"] == rendered["hw"]["cycles"]);
}
