// Hits do not depend on the BVH (docs/hw-model.md, "The BVH"): the bundled
// trace and tie-heavy scenarios (spawn points ulps from shared edges, coplanar
// duplicates) replayed over trees of Embree's three qualities and of the sweep-SAH
// builder, leaves of 1 to 32 triangles and SAH traversal costs 1 to 16, nodes of
// two precisions (on the cycle-level model with two box pools; their boxes tested
// in float32 or in the narrow format), nodes 2, 4 and 8 wide,
// functionally and on the cycle-level model, give every closest-hit ray the same triangle, distance, barycentrics and
// front/back bit, and every shadow ray (any hit) the same occlusion and verdict.
#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

namespace {

namespace fs = std::filesystem;
using vbsim::test::run_vbsim;

struct Build {
  const char* quality;  ///< Embree's quality, or "sweep-sah" for that builder
  int leaf;
  int cost;
  /// Nodes of two precisions (bvh.low_precision, rtcore-systemc's defaults),
  /// on the cycle-level model the rtcore preset (its two box pools, no pop
  /// culling, a leaf's triangles read one by one).
  bool marked = false;
  int width = 2;  ///< children per node (--bvh-width)
  bool narrow = false;  ///< marked nodes tested in the narrow format (rtcore's arithmetic)
  int block = 1;        ///< triangles the SAH prices as one test (--bvh-sah-block)
  std::string options(const fs::path& dir, bool cycle) const {
    const std::string builder = std::string(quality) == "sweep-sah" ? " --bvh-builder sweep-sah"
                                                                     : std::string(" --bvh-quality ") + quality;
    std::string o = builder + " --bvh-leaf-size " + std::to_string(leaf) + " --bvh-traversal-cost " +
                    std::to_string(cost) + " --bvh-width " + std::to_string(width) + " --bvh-sah-block " +
                    std::to_string(block);
    if (!marked) return o + (cycle ? " --preset small" : "");
    const fs::path cfg = dir / (narrow ? "narrow.json" : "marked.json");
    std::ofstream(cfg) << R"({"bvh": {"low_precision": {"mantissa_bits": 7, "t_trav_high": 0.5, "t_trav_low": 0.47,)"
                       << R"( "narrow_arithmetic": )" << (narrow ? "true" : "false") << "}}}";
    return o + " --config " + cfg.string() + (cycle ? " --preset rtcore" : "");
  }
};

std::vector<nlohmann::json> read_hits(const fs::path& p) {
  std::ifstream in(p);
  std::vector<nlohmann::json> rows;
  std::string line;
  std::getline(in, line);  // provenance
  while (std::getline(in, line)) rows.push_back(nlohmann::json::parse(line));
  return rows;
}

/// Ray id -> true for any-hit (shadow) rays.
std::map<int64_t, bool> shadow_rays(const fs::path& trace) {
  std::ifstream in(trace);
  std::map<int64_t, bool> kinds;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const nlohmann::json r = nlohmann::json::parse(line);
    kinds[r["id"].get<int64_t>()] = r.value("kind", "") == "shadow";
  }
  return kinds;
}

/// Closest-hit rays: everything of the hit; shadow rays: whether occluded, and the verdict.
nlohmann::json comparable(const nlohmann::json& hit, bool shadow) {
  if (shadow) return {{"id", hit["id"]}, {"occluded", hit["prim"].get<int64_t>() >= 0}, {"verdict", hit.value("verdict", "")}};
  nlohmann::json h = hit;
  h.erase("rejected");  // candidates rejected on the way: the work, which depends on the tree
  return h;
}

void check_independent(const fs::path& trace, const fs::path& dir, const std::string& method) {
  const auto kinds = shadow_rays(trace);
  const Build builds[] = {{"high", 4, 1},      {"medium", 4, 1},      {"low", 4, 1},         {"high", 1, 1},
                          {"high", 16, 8},     {"medium", 32, 16},    {"sweep-sah", 4, 1},   {"sweep-sah", 16, 1},
                          {"sweep-sah", 16, 1, true}, {"high", 4, 1, true},
                          {"high", 4, 1, false, 4},  {"low", 1, 1, false, 8},  {"sweep-sah", 16, 1, false, 8},
                          {"sweep-sah", 16, 1, true, 2, true},
                          {"high", 8, 2, false, 4, false, 4},  {"sweep-sah", 8, 1, false, 2, false, 4}};
  std::vector<nlohmann::json> reference;
  int n = 0;
  for (const Build& b : builds)
    for (const char* mode : {"functional", "cycle"}) {
      const std::string options = b.options(dir, std::string(mode) == "cycle");
      INFO(trace.filename().string() << ", " << method << ", " << mode << options);
      const fs::path hits = dir / ("hits" + std::to_string(n++) + ".jsonl");
      const auto r = run_vbsim("replay " + trace.string() + " -m " + method + " --mode " + mode + " -q --hits " +
                               hits.string() + options);
      INFO(r.output);
      REQUIRE(r.exit_code == 0);
      std::vector<nlohmann::json> got;
      for (const nlohmann::json& h : read_hits(hits)) got.push_back(comparable(h, kinds.at(h["id"].get<int64_t>())));
      if (reference.empty()) {
        reference = got;
        continue;
      }
      REQUIRE(got.size() == reference.size());
      size_t differ = 0;
      for (size_t i = 0; i < got.size(); ++i)
        if (got[i] != reference[i] && differ++ < 3) UNSCOPED_INFO(reference[i].dump() << " against " << got[i].dump());
      CHECK(differ == 0);
    }
}

}  // namespace

TEST_CASE("hits do not depend on the BVH: the bundled trace", "[system][bvh-options]") {
  const auto dir = vbsim::test::scratch_dir("bvh_bundled");
  const fs::path trace = fs::path(VBSIM_SOURCE_DIR) / "traces/bunny/paths.jsonl";
  for (const char* method : {"validity-bit", "none"}) check_independent(trace, dir, method);
  fs::remove_all(dir);
}

TEST_CASE("hits do not depend on the BVH: ties on shared edges and coplanar triangles", "[system][bvh-options]") {
  const auto dir = vbsim::test::scratch_dir("bvh_ties");
  for (const char* scenario : {"shared-edges", "coplanar"}) {
    const fs::path gen = dir / scenario;
    // Seed 1, 3,000 rays: the flat sheet has rays through a shared vertex or edge
    // at exactly equal distances, whose triangle depended on the tree before ties
    // went to the lowest id (rays 1638 and 12985 under Embree's low quality).
    REQUIRE(run_vbsim(std::string("gen ") + scenario + " --rays 3000 --seed 1 -q -o " + gen.string()).exit_code == 0);
    int traces = 0;
    for (const auto& e : fs::directory_iterator(gen))
      if (e.path().extension() == ".jsonl") {
        check_independent(e.path(), dir, "validity-bit");
        ++traces;
      }
    CHECK(traces == (std::string(scenario) == "coplanar" ? 1 : 3));
  }
  fs::remove_all(dir);
}

TEST_CASE("the BVH builder option is echoed in the stats, and an unknown builder is a usage error", "[system][bvh-options]") {
  const auto dir = vbsim::test::scratch_dir("bvh_builder_option");
  const fs::path trace = fs::path(VBSIM_SOURCE_DIR) / "traces/bunny/paths.jsonl";
  const fs::path stats = dir / "stats.json";
  REQUIRE(run_vbsim("replay " + trace.string() + " -q --bvh-builder sweep-sah --stats " + stats.string()).exit_code ==
          0);
  std::ifstream in(stats);
  CHECK(nlohmann::json::parse(in)["config"]["bvh"]["builder"] == "sweep-sah");
  const auto bad = run_vbsim("replay " + trace.string() + " -q --bvh-builder sah");
  INFO(bad.output);
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.output, Catch::Contains("bvh.builder") && Catch::Contains("embree, sweep-sah"));
  fs::remove_all(dir);
}
