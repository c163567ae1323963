// Files from elsewhere, second round (docs/reliability.md): deep nesting,
// repeated keys, coordinates beyond the supported range and tiny scenes,
// lying binary headers, children before their parents in score and fit, and
// errors that name the file.
#include <catch2/catch.hpp>

#include <cstring>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

const std::string kBunny = source_dir() + "/traces/bunny/bunny.obj";
const std::string kTrace = source_dir() + "/traces/bunny/paths.jsonl";

std::string header(const std::string& scene, const std::string& extra = "") {
  return "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"" + scene + "\"" + extra + "}\n";
}

std::string repeat(const std::string& s, int n) {
  std::string out;
  out.reserve(s.size() * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

/// The bundled trace's rays under another header.
std::string bunny_rays() {
  const std::string text = read_file(kTrace);
  return text.substr(text.find('\n') + 1);
}

}  // namespace

TEST_CASE("deep nesting in a known field is one error naming the file and line", "[cli][hostile]") {
  const auto dir = scratch_dir("deep_json");
  const int depth = 80000;  // crashed the reader before (depth 60,000 was refused cleanly)
  const auto id = dir / "id.jsonl", light = dir / "light.jsonl", cfg = dir / "c.json";
  write_file(id, header(kBunny) + "{\"id\": " + repeat("[", depth) + repeat("]", depth) + ", \"o\":[0,0,0], \"d\":[0,0,1]}\n");
  write_file(light, header(kBunny, ",\"light\":" + repeat("[", depth) + repeat("]", depth)));
  write_file(cfg, "{\"validity_bit\": " + repeat("{\"eps\": ", depth) + "1" + repeat("}", depth) + "}\n");
  RunResult r = run_vbsim("replay " + id.string() + " -q");
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains(id.string() + ":2: field 'id': nested deeper than 64 levels"));
  r = run_vbsim("check " + light.string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains(light.string() + ":1: field 'light': nested deeper than 64 levels"));
  const auto vbt = dir / "light.vbt";  // the binary form's header is the same JSON
  r = run_vbsim("convert " + light.string() + " -o " + vbt.string() + " -q");
  CHECK(r.exit_code == 1);
  r = run_vbsim("replay " + kTrace + " -q --config " + cfg.string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains(cfg.string() + ": line 1: JSON nested deeper than 64 levels"));
}

TEST_CASE("a key twice in a config is refused, as in traces", "[cli][hostile]") {
  const auto dir = scratch_dir("dup_key");
  const auto cfg = dir / "c.json";
  write_file(cfg, "{\"hw\": {\"cores\": 2, \"cores\": 4}}\n");
  const RunResult r = run_vbsim("replay " + kTrace + " -q --mode cycle --config " + cfg.string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains(cfg.string() + ": field 'hw.cores': appears twice"));
}

TEST_CASE("vertices beyond +-2^126 are refused naming the file and vertex, before Embree sees them", "[cli][hostile]") {
  const auto dir = scratch_dir("huge_coords");
  const std::string box = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                          "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  write_file(dir / "huge.ply", box + "0 0 0\n1 0 0\n1 1 0\n3e38 1 1\n3 0 1 2\n3 0 2 3\n");
  write_file(dir / "edge.ply", box + "0 0 0\n1 0 0\n1 1 0\n-85070591730234615865843651857942052864 1 1\n3 0 1 2\n3 0 2 3\n");  // -2^126: in range
  const std::string ray = "{\"id\":0,\"o\":[0.5,0.25,5],\"d\":[0,0,-1]}\n";
  write_file(dir / "huge.jsonl", header(dir.string() + "/huge.ply") + ray);
  write_file(dir / "edge.jsonl", header(dir.string() + "/edge.ply") + ray);
  // A header transform that moves the bunny to 3e38.
  write_file(dir / "moved.jsonl",
             header(kBunny, ",\"transform\":[1,0,0,3e38,0,1,0,0,0,0,1,0,0,0,0,1]") + ray);
  for (const char* command : {"replay", "oracle", "score", "render"}) {
    INFO(command);
    const std::string out = " -o " + (dir / "out.png").string();
    const std::string args = std::string(command) + " " + (dir / "huge.jsonl").string() +
                             (std::string(command) == "oracle" ? " -o " + (dir / "o.jsonl").string()
                                                               : std::string(command) == "render" ? out : "") +
                             " -q";
    const RunResult r = run_vbsim(args);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Catch::Contains("huge.ply': a PLY face (triangle 1) has the vertex (3e+38, 1, 1), beyond "
                                         "the supported coordinate range"));
  }
  RunResult r = run_vbsim("replay " + (dir / "moved.jsonl").string() + " -q");
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("after the transform, beyond the supported coordinate range"));
  r = run_vbsim("replay " + (dir / "edge.jsonl").string() + " -q");
  CHECK(r.exit_code == 0);
}

TEST_CASE("tiny scenes that are valid floats load, build and replay", "[cli][hostile]") {
  // The bunny scaled by 1e-25 .. 1e-35 was refused with Embree's "depth limit
  // reached". Scales where the float32 testers still resolve the bunny give
  // every camera ray its exact answer; below, the replay scores what they miss.
  const auto dir = scratch_dir("tiny_scenes");
  const std::string rays = bunny_rays();
  for (const char* scale : {"1e-12", "1e-25", "1e-30", "1e-35"}) {
    INFO(scale);
    const std::string s(scale);
    const std::string transform = ",\"transform\":[" + s + ",0,0,0,0," + s + ",0,0,0,0," + s + ",0,0,0,0,1]";
    // Camera rays only, their origins scaled as the scene, without expectations (the oracle fills them in).
    std::string text = header(kBunny, transform);
    const double f = std::stod(s);
    size_t at = 0;
    int cameras = 0;
    while (at < rays.size()) {
      const size_t end = rays.find('\n', at);
      nlohmann::json ray = nlohmann::json::parse(rays.substr(at, end - at));
      at = end + 1;
      if (ray.contains("parent")) continue;
      ray.erase("expect");
      for (auto& c : ray["o"]) c = static_cast<float>(c.get<double>() * f);
      text += ray.dump() + "\n";
      ++cameras;
    }
    const auto trace = dir / ("t" + s + ".jsonl"), scored = dir / ("o" + s + ".jsonl");
    write_file(trace, text);
    REQUIRE(run_vbsim("oracle " + trace.string() + " -o " + scored.string() + " -q").exit_code == 0);
    const auto stats = dir / ("s" + s + ".json");
    const RunResult r = run_vbsim("replay " + scored.string() + " -q --stats " + stats.string());
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(read_file(stats));
    CHECK(j["rays"] == cameras);
    if (s == "1e-12") CHECK(j["verdicts"]["correct"] == cameras);
  }
}

TEST_CASE("a binary header whose stated length runs into the records is refused", "[cli][hostile]") {
  const auto dir = scratch_dir("lying_header");
  const auto vbt = dir / "t.vbt", lie = dir / "lie.vbt";
  REQUIRE(run_vbsim("convert " + kTrace + " -o " + vbt.string() + " -q").exit_code == 0);
  std::string bytes = read_file(vbt);
  uint32_t n = 0;
  std::memcpy(&n, bytes.data() + 12, 4);
  const uint32_t covering = (n + 7) / 8 * 8 + 96;  // the header, its padding and the first record
  std::memcpy(bytes.data() + 12, &covering, 4);
  write_file(lie, bytes);
  for (const std::string& args : {"replay " + lie.string() + " -q", "check " + lie.string(),
                                  "convert " + lie.string() + " -o " + (dir / "c.jsonl").string() + " -q"}) {
    INFO(args);
    const RunResult r = run_vbsim(args);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Catch::Contains("lie.vbt: header: the stated header length"));
  }
  // A length within the padding still ends at the object's last byte: refused as well.
  std::memcpy(bytes.data() + 12, &n, 4);
  bytes[16 + n - 1] = ' ';
  write_file(lie, bytes);
  CHECK(run_vbsim("check " + lie.string()).exit_code == 1);
}

TEST_CASE("score and fit refuse a child before its parent, naming the file and line", "[cli][hostile]") {
  const auto dir = scratch_dir("score_order");
  const std::string rays = bunny_rays();
  const std::string first = rays.substr(0, rays.find('\n') + 1);
  // A ray that is its own parent, then one whose parent comes later.
  const std::string self = "{\"id\":5000,\"parent\":5000,\"kind\":\"shadow\",\"o\":[0,0.1,0.05],\"d\":[0,1,0],"
                           "\"expect\":{\"prim\":-1}}\n";
  const std::string forward = "{\"id\":5001,\"parent\":5002,\"kind\":\"shadow\",\"o\":[0,0.1,0.05],\"d\":[0,1,0],"
                              "\"expect\":{\"prim\":-1}}\n{\"id\":5002,\"o\":[0,0.1,5],\"d\":[0,0,-1],"
                              "\"expect\":{\"prim\":-1}}\n";
  write_file(dir / "self.jsonl", header(kBunny) + first + self);
  write_file(dir / "forward.jsonl", header(kBunny) + first + forward);
  for (const auto& [name, message] : {std::pair<const char*, const char*>{"self", "names itself as its parent"},
                                      {"forward", "child before parent"}}) {
    const std::string trace = (dir / (std::string(name) + ".jsonl")).string();
    for (const std::string& args : {"score " + trace + " --methods tmin --testers three-half-plane -q",
                                    "score " + trace + " --methods tmin --testers three-half-plane --mode cycle -q",
                                    "fit " + trace + " --params tmin-eps -q"}) {
      INFO(args);
      const RunResult r = run_vbsim(args);
      CHECK(r.exit_code == 1);
      CHECK_THAT(r.output, Catch::Contains(trace + ":3: field 'parent'") && Catch::Contains(message));
    }
  }
}

TEST_CASE("config checks across fields name the config file", "[cli][hostile]") {
  const auto dir = scratch_dir("config_names");
  const auto cfg = dir / "c.json";
  write_file(cfg, "{\"hw\": {\"memory\": {\"l1\": {\"hit_latency\": 0}}}}\n");
  RunResult r = run_vbsim("replay " + kTrace + " -q --mode cycle --config " + cfg.string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains(cfg.string() + ": field 'hw.memory.l1.hit_latency': must be at least 1 cycle"));
  write_file(cfg, "{\"hw\": {\"memory\": {\"dram_bytes_per_cycle\": 1e-5}}}\n");
  r = run_vbsim("replay " + kTrace + " -q --mode cycle --config " + cfg.string());
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains(cfg.string() + ": field 'hw.memory.dram_bytes_per_cycle': too small"));
}

TEST_CASE("render names the problem with its option or scene", "[cli][hostile]") {
  const auto dir = scratch_dir("render_names");
  const std::string png = (dir / "x.png").string();
  RunResult r = run_vbsim("render " + kBunny + " -o " + png + " --camera 1,2,3,1,2,3 --size 8x8");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("option '--camera': eye and target coincide"));
  r = run_vbsim("render " + kBunny + " -o " + png + " --camera 3e38,0,0,0,0,0 --size 8x8");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("option '--camera'") && Catch::Contains("beyond the supported coordinate range"));
}
