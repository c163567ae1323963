// vbsim score end to end: the same counts as `vbsim replay`, the committed
// counts of a small fixed-seed scenario (CI subset), the markdown page, and
// errors on bad input.
#include <catch2/catch.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "run_vbsim.h"

using namespace vbsim::test;
using nlohmann::json;

namespace {

const json* find_row(const json& score, const std::string& family, const std::string& method,
                     const std::string& tester, const std::string& kind) {
  for (const auto& r : score["rows"])
    if (r["family"] == family && r["method"] == method && r["tester"] == tester && r["kind"] == kind) return &r;
  return nullptr;
}

}  // namespace

TEST_CASE("score counts equal vbsim replay counts for the same method", "[system][score]") {
  const auto dir = scratch_dir("score_replay");
  const auto cases = (dir / "paths").string();
  REQUIRE(run_vbsim("gen paths --rays 12 --seed 5 -o " + cases).exit_code == 0);
  const std::string methods = "none,validity-bit:vb-eps-mode=fixed:vb-eps=1e-5,tmin:tmin-eps=1e-3,offset-adaptive+primid";
  const RunResult sr = run_vbsim("score " + cases + " -q --methods " + methods +
                                 " --testers three-half-plane,moller-trumbore --out " + (dir / "s.json").string());
  INFO(sr.output);
  REQUIRE(sr.exit_code == 0);
  const json score = json::parse(read_file(dir / "s.json"));
  // The same configurations through `vbsim replay`, spelled as its options.
  const std::vector<std::pair<std::string, std::string>> replays = {
      {"none", "-m none"},
      {"validity-bit:vb-eps-mode=fixed:vb-eps=1e-5", "-m validity-bit --vb-eps-mode fixed --vb-eps 1e-5"},
      {"tmin:tmin-eps=1e-3", "-m tmin --tmin-eps 1e-3"},
      {"offset-adaptive+primid", "-m offset-adaptive+primid"}};
  for (const auto& [label, options] : replays)
    for (const std::string tester : {"three-half-plane", "moller-trumbore"}) {
      const auto stats_path = (dir / "stats.json").string();
      const RunResult r = run_vbsim("replay " + cases + "/paths.jsonl -q --stats " + stats_path + " " + options +
                                    " --tester " + tester);
      REQUIRE(r.exit_code == 0);
      const json stats = json::parse(read_file(stats_path));
      INFO(label << " " << tester);
      const json* all = find_row(score, "paths", label, tester, "all");
      REQUIRE(all);
      CHECK((*all)["counts"] == stats["verdicts"]);
      CHECK((*all)["rays"] == stats["rays"]);
      for (const char* k : {"candidates", "suspects", "rejected"})
        CHECK((*all)["avoidance"][k] == stats["avoidance"][k]);
      for (const auto& [kind, ks] : stats["by_kind"].items()) {
        const json* row = find_row(score, "paths", label, tester, kind);
        REQUIRE(row);
        CHECK((*row)["counts"] == ks["verdicts"]);
        CHECK((*row)["avoidance"]["rejected"] == ks["avoidance"]["rejected"]);
      }
    }
  // One thread gives the same table as two.
  REQUIRE(run_vbsim("score " + cases + " -q --threads 1 --methods " + methods +
                    " --testers three-half-plane,moller-trumbore --out " + (dir / "s1.json").string())
              .exit_code == 0);
  const json one = json::parse(read_file(dir / "s1.json"));
  REQUIRE(one["rows"].size() == score["rows"].size());
  for (size_t i = 0; i < one["rows"].size(); ++i) {
    CHECK(one["rows"][i]["counts"] == score["rows"][i]["counts"]);
    CHECK(one["rows"][i]["method"] == score["rows"][i]["method"]);
  }
}

TEST_CASE("score of the CI scenarios matches the committed counts", "[system][score][ci]") {
  // Regenerate the expectations with scripts/update_score_expected.py.
  const json expected = json::parse(read_file(source_dir() + "/traces/ci/score.expected.json"));
  const auto dir = scratch_dir("score_ci");
  std::string paths;
  for (const auto& g : expected["gen"]) {
    const auto out = (dir / g["family"].get<std::string>()).string();
    std::string args = g["args"].get<std::string>();
    for (size_t at; (at = args.find("{source}")) != std::string::npos;) args.replace(at, 8, source_dir());
    const RunResult r = run_vbsim("gen " + args + " -o " + out);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    paths += " " + out;
  }
  paths += " " + source_dir() + "/" + expected["bundled"].get<std::string>();
  const RunResult r = run_vbsim("score" + paths + " -q --methods " + expected["methods"].get<std::string>() +
                                " --testers " + expected["testers"].get<std::string>() + " --out " +
                                (dir / "score.json").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const json got = json::parse(read_file(dir / "score.json"));
  size_t compared = 0;
  for (const auto& want : expected["rows"]) {
    const json* row = find_row(got, want["family"], want["method"], want["tester"], want["kind"]);
    INFO(want.dump());
    REQUIRE(row);
    CHECK((*row)["counts"] == want["counts"]);
    CHECK((*row)["avoidance"]["suspects"] == want["suspects"]);
    CHECK((*row)["avoidance"]["rejected"] == want["rejected"]);
    ++compared;
  }
  CHECK(compared == got["rows"].size());
  CHECK(compared > 20);
}

TEST_CASE("score writes a generated markdown page with intervals", "[system][score]") {
  const auto dir = scratch_dir("score_md");
  const auto md = (dir / "accuracy.md").string();
  const RunResult r = run_vbsim("score " + source_dir() + "/traces/bunny -q --methods none,tmin --testers "
                                "three-half-plane --accuracy-md " + md + " --regenerate-with 'scripts/make_results.sh'");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string text = read_file(md);
  CHECK_THAT(text, Catch::Contains("do not edit by hand") && Catch::Contains("    scripts/make_results.sh") &&
                       Catch::Contains("## bunny") &&
                       Catch::Contains("| `tmin` | three-half-plane | secondary | 808 |") &&
                       Catch::Contains("| `tmin` | three-half-plane | primary | 200 |"));
  // tmin has no self hit among the 808 secondary rays of the bundled trace:
  // rate 0, upper bound z^2/(n+z^2) per million.
  CHECK_THAT(text, Catch::Contains("| 0 [0, 4732] |"));
  // The summary (secondary rays only): 369 self hits of 808 rays without a
  // method (the committed expectations of the default trace) are 456683 per million.
  CHECK_THAT(text, Catch::Contains("## Summary, three-half-plane tester: secondary-ray errors per million") &&
                       Catch::Contains("| `none` | 456683 [422623, 491153] |") &&
                       Catch::Contains("| `tmin` | 0 [0, 4732] |"));
  // The methods' own energy per ray: none has none, tmin's 7 operations cost 58.9 pJ
  // per ray at the shipped figures (3 multiplies, 2 adds, a square root, a divide).
  CHECK_THAT(text, Catch::Contains("### The method's energy per ray, pJ, three-half-plane tester") &&
                       Catch::Contains("| `none` | 0 |") && Catch::Contains("| `tmin` | 58.9 |"));
  // The trade-off table of the family: the same rate with its interval, the 200
  // camera rays' misses with theirs (0: upper bound z^2/(n+z^2) per million),
  // bits per ray, operations per ray, and the operations' energy per ray (no
  // method: 0 pJ of its own).
  CHECK_THAT(text, Catch::Contains("| `none` | three-half-plane | 456683 [422623, 491153] | 808 | 0 [0, 18845] | 259 | 0 | "));
  CHECK_THAT(text, Catch::Contains("| pJ/ray (ops) | method pJ/ray |"));
}

TEST_CASE("score --mode cycle times every configuration on the traces it scores", "[system][score][cycle]") {
  const auto dir = scratch_dir("score_cycle");
  const std::string bunny = source_dir() + "/traces/bunny";
  const auto cyc = (dir / "cycle.json").string(), fun = (dir / "functional.json").string();
  const auto md = (dir / "accuracy.md").string();
  RunResult r = run_vbsim("score " + bunny + " -q --methods none,offset-adaptive --testers three-half-plane,"
                          "pbrt-watertight --mode cycle --preset small --cycle-testers three-half-plane --out " +
                          cyc + " --accuracy-md " + md);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  r = run_vbsim("score " + bunny + " -q --methods none,offset-adaptive --testers three-half-plane,pbrt-watertight "
                "--out " + fun);
  REQUIRE(r.exit_code == 0);
  const json c = json::parse(read_file(cyc)), f = json::parse(read_file(fun));
  REQUIRE(c["rows"].size() == f["rows"].size());
  for (size_t i = 0; i < c["rows"].size(); ++i) CHECK(c["rows"][i]["counts"] == f["rows"][i]["counts"]);
  // The cycles of one trace are those of `vbsim replay --mode cycle` on it.
  const auto stats = (dir / "replay.json").string();
  REQUIRE(run_vbsim("replay " + bunny + "/paths.jsonl -q --mode cycle --preset small -m offset-adaptive --stats " +
                    stats).exit_code == 0);
  const json replay = json::parse(read_file(stats));
  const json* timed = find_row(c, "bunny", "offset-adaptive", "three-half-plane", "all");
  REQUIRE(timed);
  REQUIRE(timed->contains("cycle"));
  const json& cy = (*timed)["cycle"];
  CHECK(cy["preset"] == "small");
  CHECK(cy["rays"] == 1008);
  CHECK(cy["cycles"] == replay["hw"]["cycles"]);
  CHECK(cy["cycles_per_ray"].get<double>() == Approx(cy["cycles"].get<double>() / 1008));
  CHECK(cy["rays_per_cycle"].get<double>() == Approx(1008 / cy["cycles"].get<double>()));
  // Only the testers asked for are timed.
  CHECK_FALSE(find_row(c, "bunny", "offset-adaptive", "pbrt-watertight", "all")->contains("cycle"));
  CHECK_THAT(read_file(md), Catch::Contains("| cycles/ray | rays/cycle |") &&
                                Catch::Contains("### Cycles per ray, small preset, three-half-plane tester"));
}

// Score reads a trace in blocks of 16384 rays; in cycle mode the cycle-level
// model replays the whole trace once, streamed (not block by block, which
// would drain the pipeline at every block boundary), so its cycles are those
// of one `vbsim replay --mode cycle` also on a trace longer than a block.
TEST_CASE("score --mode cycle replays a trace longer than a block in one cycle-level run", "[system][score][cycle]") {
  const auto dir = scratch_dir("score_cycle_blocks");
  const auto cases = (dir / "paths").string();
  REQUIRE(run_vbsim("gen paths --rays 4000 --seed 3 -q -o " + cases).exit_code == 0);
  const auto cyc = (dir / "cycle.json").string(), stats = (dir / "replay.json").string();
  const RunResult r = run_vbsim("score " + cases + " -q --methods offset-adaptive --testers three-half-plane "
                                "--mode cycle --preset small --out " + cyc);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  REQUIRE(run_vbsim("replay " + cases + "/paths.jsonl -q --mode cycle --preset small -m offset-adaptive --stats " +
                    stats).exit_code == 0);
  const json c = json::parse(read_file(cyc)), replay = json::parse(read_file(stats));
  REQUIRE(replay["rays"].get<int64_t>() > 16384);
  const json* row = find_row(c, "paths", "offset-adaptive", "three-half-plane", "all");
  REQUIRE(row);
  CHECK((*row)["rays"] == replay["rays"]);
  CHECK((*row)["counts"] == replay["verdicts"]);
  CHECK((*row)["cycle"]["rays"] == replay["rays"]);
  CHECK((*row)["cycle"]["cycles"] == replay["hw"]["cycles"]);
}

TEST_CASE("score rejects bad input with a clear message", "[system][score][errors]") {
  const auto dir = scratch_dir("score_errors");
  const std::string bunny = source_dir() + "/traces/bunny";
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"score " + (dir / "nothing").string(), "no such trace file or directory"},
      {"score " + dir.string(), "no trace files"},
      {"score " + bunny + " --methods warp", "unknown value \"warp\""},
      {"score " + bunny + " --methods tmin:eps=3", "unknown key 'eps'"},
      {"score " + bunny + " --testers slab", "unknown tester 'slab'"},
      {"score " + bunny + " --preset small", "need '--mode cycle'"},
      {"score " + bunny + " --mode timed", "'timed' is not a mode"},
      {"score " + bunny + " --mode cycle --preset huge", "huge"},
      {"score " + bunny + " " + bunny, "a second scenario family named 'bunny'"},
      {"score " + bunny + " --threads 0", "--threads"},
      {"score " + bunny + " --methods none --out /nonexistent/dir/s.json", "/nonexistent/dir/s.json: cannot create"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_vbsim(c.args);
    INFO(c.args << "\n" << r.output);
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.output, Catch::Contains(c.message));
  }
  // A trace with a broken line names the file and the line.
  const std::string trace = read_file(bunny + "/paths.jsonl");
  const size_t second_line = trace.find('\n', trace.find('\n') + 1) + 1;
  write_file(dir / "bad.jsonl", trace.substr(0, second_line) + "{\"id\": }\n");
  write_file(dir / "bunny.obj", read_file(bunny + "/bunny.obj"));
  const RunResult r = run_vbsim("score " + (dir / "bad.jsonl").string() + " --methods none");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("bad.jsonl") && Catch::Contains("3"));
}

TEST_CASE("vbsim scenarios lists every scenario gen accepts", "[system][score]") {
  const RunResult r = run_vbsim("scenarios --names");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::StartsWith("paths\n") || Catch::Contains("\npaths\n"));
  const RunResult bad = run_vbsim("gen no-such-scenario -o /tmp/vbsim_none");
  CHECK_THAT(bad.output, Catch::Contains("scenarios: " + r.output.substr(0, r.output.find('\n'))));
}

TEST_CASE("score --mode cycle gives every cost of the run: the replay's energy per ray and chip area",
          "[system][score][cycle][energy]") {
  const auto dir = scratch_dir("score_cycle_costs");
  const std::string trace = source_dir() + "/traces/bunny/paths.jsonl";
  for (const std::string& tech : {std::string(), source_dir() + "/model/energy/tech/7nm.json"}) {
    INFO(tech);
    const std::string tech_option = tech.empty() ? "" : " --tech " + tech;
    const auto cyc = (dir / "cycle.json").string(), stats = (dir / "replay.json").string();
    const RunResult r = run_vbsim("score " + trace + " --methods validity-bit --testers three-half-plane --mode cycle "
                                  "--preset small --threads 1" + tech_option + " --out " + cyc);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    REQUIRE(run_vbsim("replay " + trace + " -q --mode cycle --preset small -m validity-bit" + tech_option +
                      " --stats " + stats).exit_code == 0);
    const json c = json::parse(read_file(cyc)), replay = json::parse(read_file(stats));
    const json* row = find_row(c, "paths", "validity-bit", "three-half-plane", "all");
    REQUIRE(row);
    const json& cy = (*row)["cycle"];
    // The same doubles, not merely close: one trace, one run, the same pricing.
    CHECK(cy["energy_per_ray_pj"].get<double>() == replay["hw"]["energy"]["per_ray_pj"].get<double>());
    CHECK(cy["total_pj"].get<double>() == replay["hw"]["energy"]["total_pj"].get<double>());
    CHECK(cy["chip_mm2"].get<double>() == replay["hw"]["area"]["chip_mm2"].get<double>());
    CHECK(cy["tech"] == replay["hw"]["energy"]["tech"]);
    CHECK(cy["energy_per_ray_pj"].get<double>() > (*row)["energy"]["per_ray_pj"].get<double>());  // + memory, leakage
    // The printed table names every column's unit: the model's cycles and the host's speed apart.
    CHECK_THAT(r.output, Catch::Contains("cycles/ray") && Catch::Contains("pJ/ray") && Catch::Contains("chip mm2") &&
                             Catch::Contains("host rays/s"));
    CHECK_THAT(r.output, Catch::Contains(fmt::format("{:.5g}", cy["energy_per_ray_pj"].get<double>())) &&
                             Catch::Contains(fmt::format("{:.4f}", cy["chip_mm2"].get<double>())));
  }
}
