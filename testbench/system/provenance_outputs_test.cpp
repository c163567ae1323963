// Every output file records the version, the command line and the SHA-256 of
// its inputs; the checksums are checked here against coreutils' sha256sum.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

std::string sha256sum(const std::string& path) {
  const RunResult r = [&] {
    RunResult out;
    FILE* pipe = popen(("sha256sum '" + path + "'").c_str(), "r");
    char buf[256];
    while (pipe && fgets(buf, sizeof buf, pipe)) out.output += buf;
    out.exit_code = pipe ? pclose(pipe) : -1;
    return out;
  }();
  return r.output.substr(0, 64);
}

void check_provenance(const nlohmann::json& p, const std::string& command_word,
                      const std::vector<std::string>& inputs) {
  const auto version = run_vbsim_split("--version").out;
  CHECK(version == "vbsim " + p["version"].get<std::string>() + " (revision " + p["revision"].get<std::string>() +
                       ")\n");
  REQUIRE(p["command"].size() > 1);
  CHECK(p["command"][1] == command_word);
  REQUIRE(p["inputs"].size() == inputs.size());
  for (size_t i = 0; i < inputs.size(); ++i) {
    INFO(inputs[i]);
    CHECK(p["inputs"][i]["path"] == inputs[i]);
    CHECK(p["inputs"][i]["sha256"] == sha256sum(inputs[i]));
  }
}

/// The JSON after `marker` up to the end of its line.
nlohmann::json json_after(const std::string& text, const std::string& marker, const std::string& end = "\n") {
  const size_t at = text.find(marker);
  REQUIRE(at != std::string::npos);
  const size_t from = at + marker.size();
  return nlohmann::json::parse(text.substr(from, text.find(end, from) - from));
}

/// The text of a PNG's iTXt chunk `key` (uncompressed, no language tag).
nlohmann::json png_note(const std::string& png, const std::string& key) {
  const size_t type = png.find("iTXt" + key + std::string(1, '\0'));
  REQUIRE(type != std::string::npos);
  const auto u8 = [&](size_t i) { return static_cast<uint32_t>(static_cast<uint8_t>(png[i])); };
  const uint32_t length = u8(type - 4) << 24 | u8(type - 3) << 16 | u8(type - 2) << 8 | u8(type - 1);
  const size_t text = type + 4 + key.size() + 5;
  return nlohmann::json::parse(png.substr(text, type + 4 + length - text));
}

}  // namespace

TEST_CASE("stats, hits, VCD and timeline name what made them", "[cli][provenance]") {
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  const std::string scene = source_dir() + "/traces/bunny/bunny.obj";
  const auto dir = scratch_dir("provenance_replay");
  write_file(dir / "c.json", R"({"method": "tmin"})");
  const std::string cfg = (dir / "c.json").string();
  REQUIRE(run_vbsim("replay " + trace + " -q --mode cycle --config " + cfg + " --stats " + (dir / "s.json").string() +
                    " --hits " + (dir / "h.jsonl").string() + " --vcd " + (dir / "w.vcd").string() + " --timeline " +
                    (dir / "t.json").string())
              .exit_code == 0);
  // The technology file that priced the energy is an input too (the shipped default).
  const std::string tech = source_dir() + "/model/energy/tech/45nm.json";
  const std::vector<std::string> inputs = {trace, scene, cfg, tech};
  check_provenance(nlohmann::json::parse(read_file(dir / "s.json"))["provenance"], "replay", inputs);
  const std::string hits = read_file(dir / "h.jsonl");
  check_provenance(nlohmann::json::parse(hits.substr(0, hits.find('\n')))["provenance"], "replay", inputs);
  const std::string vcd = read_file(dir / "w.vcd");
  CHECK(vcd.rfind("$comment vbsim-provenance ", 0) == 0);
  check_provenance(json_after(vcd, "$comment vbsim-provenance ", " $end"), "replay", inputs);
  CHECK(vcd.find("$timescale") != std::string::npos);  // the rest of the VCD follows
  check_provenance(nlohmann::json::parse(read_file(dir / "t.json"))["otherData"]["provenance"], "replay", inputs);
}

TEST_CASE("traces, scenes, score tables and images name what made them", "[cli][provenance]") {
  const auto dir = scratch_dir("provenance_files");
  const std::string g = (dir / "g").string();
  REQUIRE(run_vbsim("gen coplanar --rays 5 -q -o " + g).exit_code == 0);
  const std::string trace = g + "/coplanar.jsonl", ply = g + "/coplanar.ply";
  check_provenance(json_after(read_file(trace), "\"provenance\":", "}\n"), "gen", {});
  check_provenance(json_after(read_file(ply), "comment vbsim-provenance "), "gen", {});
  const std::string vbt = (dir / "c.vbt").string();
  REQUIRE(run_vbsim("convert -q " + trace + " -o " + vbt).exit_code == 0);
  REQUIRE(run_vbsim("oracle -q " + vbt + " -o " + (dir / "o.jsonl").string()).exit_code == 0);
  const nlohmann::json oracle = json_after(read_file(dir / "o.jsonl"), "\"provenance\":", "}\n");
  // The oracle's input is the binary trace and the scene its header names.
  check_provenance(oracle, "oracle", {vbt, (dir / "g" / "coplanar.ply").string()});
  const std::string md = (dir / "a.md").string();
  REQUIRE(run_vbsim("score -q " + trace + " --methods none --testers three-half-plane --out " +
                    (dir / "s.json").string() + " --accuracy-md " + md)
              .exit_code == 0);
  const std::string tech = source_dir() + "/model/energy/tech/45nm.json";
  check_provenance(nlohmann::json::parse(read_file(dir / "s.json"))["provenance"], "score", {trace, tech});
  check_provenance(json_after(read_file(md), "<!-- vbsim-provenance ", " -->"), "score", {trace, tech});
  const std::string png = (dir / "i.png").string();
  REQUIRE(run_vbsim("render -q " + ply + " --size 4x3 -o " + png).exit_code == 0);
  check_provenance(png_note(read_file(png), "vbsim-provenance"), "render", {ply});
}
