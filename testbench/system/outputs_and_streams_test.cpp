// Outputs, second round: render, fit and bench refuse to overwrite what they
// read; outputs reached through a dangling symbolic link are compared by what
// they would create; an empty path is a usage error; data on stdout that does
// not arrive fails the run; SIGTERM ends every command with 130; -q on check
// and bench; pipes to score and fit are refused with the reason.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {
const std::string kBunny = source_dir() + "/traces/bunny/bunny.obj";
const std::string kTrace = source_dir() + "/traces/bunny/paths.jsonl";
}  // namespace

TEST_CASE("render, fit and bench refuse an output that is an input, which stays whole", "[cli][outputs]") {
  const auto dir = scratch_dir("outputs_inputs");
  const auto scene = dir / "s.obj", trace = dir / "t.jsonl", cfg = dir / "c.json";
  write_file(scene, read_file(kBunny));
  write_file(trace, "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"" + kBunny + "\"}\n" +
                        read_file(kTrace).substr(read_file(kTrace).find('\n') + 1));
  write_file(cfg, "{}\n");
  std::filesystem::create_symlink(scene, dir / "link.obj");
  const std::string scene_before = read_file(scene), trace_before = read_file(trace);
  struct Case {
    std::string args, role;
  };
  const std::vector<Case> cases = {
      {"render " + scene.string() + " -o " + scene.string(), "option '--out'"},
      {"render " + scene.string() + " -o " + (dir / "link.obj").string(), "option '--out'"},
      {"render " + scene.string() + " -o " + (dir / "x.png").string() + " --config " + cfg.string() + " --stats " +
           cfg.string(),
       "option '--stats'"},
      {"fit " + trace.string() + " --params tmin-eps --json " + trace.string(), "option '--json'"},
      {"bench --scene " + scene.string() + " --rays 10 --json " + scene.string(), "option '--json'"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const RunResult r = run_vbsim(c.args + " -q");
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Catch::Contains(c.role) && Catch::Contains("this run reads; refusing to overwrite it"));
  }
  CHECK(read_file(scene) == scene_before);
  CHECK(read_file(trace) == trace_before);
  CHECK(read_file(cfg) == "{}\n");
}

TEST_CASE("two outputs through a dangling symbolic link are one file", "[cli][outputs]") {
  const auto dir = scratch_dir("dangling");
  std::filesystem::create_symlink(dir / "target.json", dir / "link.json");
  const RunResult r = run_vbsim("replay " + kTrace + " -q --stats " + (dir / "link.json").string() + " --hits " +
                                (dir / "target.json").string());
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("also the output of option '--stats'"));
  CHECK_FALSE(std::filesystem::exists(dir / "target.json"));
}

TEST_CASE("an empty path or argument is a usage error", "[cli][outputs]") {
  RunResult r = run_vbsim("replay " + kTrace + " -q --stats ''");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("option '--stats': empty value"));
  r = run_vbsim("convert " + kTrace + " -o ''");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("option '--out': empty value"));
  r = run_vbsim("check ''");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("argument 'trace': empty value"));
}

TEST_CASE("data on stdout that does not arrive fails the run", "[cli][outputs]") {
  for (const std::string& args : {"replay " + kTrace, "check " + kTrace,
                                  "score " + kTrace + " --methods tmin --testers three-half-plane"}) {
    INFO(args);
    RunResult r = run_vbsim_raw(args + " 2>&1 >/dev/full");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Catch::Contains("vbsim: error: standard output: No space left on device"));
    r = run_vbsim_raw(args + " 2>&1 >&-");  // stdout closed
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Catch::Contains("vbsim: error: standard output: Bad file descriptor"));
  }
  // A closed pipe: the hits (about 100 KB, more than a pipe holds) going to
  // stdout meet a reader that never reads and has gone: an error, not SIGPIPE.
  for (const std::string& out : {std::string("--hits /dev/stdout"), std::string("")}) {
    const std::string args = out.empty() ? " replay " + kTrace + " --method validity-bit" : " replay " + kTrace + " -q " + out;
    const RunResult r = run_command("bash -c '" + std::string(VBSIM_BINARY) + args +
                                    " 2>/dev/null | true; echo \"status ${PIPESTATUS[0]}\"'");
    INFO(args);
    if (!out.empty()) CHECK_THAT(r.output, Catch::Contains("status 1"));
    CHECK_THAT(r.output, !Catch::Contains("status 141"));
  }
  // Quiet runs print nothing and so succeed whatever stdout is.
  CHECK(run_vbsim_raw("replay " + kTrace + " -q >/dev/full").exit_code == 0);
}

TEST_CASE("SIGTERM ends any command with 130 and leaves no partial output", "[cli][interrupt]") {
  const auto dir = scratch_dir("sigterm_any");
  const auto big = dir / "big.jsonl";
  // Enough camera rays that convert and oracle run for a while.
  std::string text = "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":\"" + kBunny + "\"}\n";
  for (int i = 0; i < 300000; ++i)
    text += "{\"id\":" + std::to_string(i) + ",\"o\":[0,0.1,5],\"d\":[" + std::to_string((i % 97) * 1e-4) + ",0,-1]}\n";
  write_file(big, text);
  for (const char* command : {"convert", "oracle"}) {
    INFO(command);
    const std::string out = (dir / (std::string(command) + ".vbt")).string();
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      execl(VBSIM_BINARY, VBSIM_BINARY, command, big.c_str(), "-o", out.c_str(), "-q", static_cast<char*>(nullptr));
      _exit(127);
    }
    const bool writing = wait_for_file(dir, ".partial-");  // the output's temporary: the command is writing
    kill(child, SIGTERM);
    int status = 0;
    waitpid(child, &status, 0);
    REQUIRE(writing);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 130);
    for (const auto& e : std::filesystem::directory_iterator(dir))
      CHECK(e.path().filename().string() == "big.jsonl");
  }
}

TEST_CASE("check and bench take -q, score and fit say why a pipe cannot be read", "[cli]") {
  RunResult r = run_vbsim("check " + kTrace + " -q");
  CHECK(r.exit_code == 0);
  CHECK(r.output.empty());
  r = run_vbsim("bench --rays 50 --repeats 1 -q");
  CHECK(r.exit_code == 0);
  CHECK(r.output.empty());
  r = run_vbsim("bench --rays 50 --repeats 1 --embree-accel bvh4.triangle4v");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("tri_accel bvh4.triangle4v") && Catch::Contains("same triangle on 50 of 50"));
  r = run_vbsim("bench --rays 50 --repeats 1 --embree-accel bvh4.nonesuch -q");  // not a silent fallback
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("unknown triangle acceleration structure bvh4.nonesuch"));
  r = run_vbsim_bash("score <(cat " + kTrace + ") --methods tmin --testers three-half-plane -q");
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("not a regular file (a pipe or a device)"));
  r = run_vbsim_bash("fit <(cat " + kTrace + ") --params tmin-eps -q");
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("not a regular file (a pipe or a device)"));
}

TEST_CASE("gen says when --seed has no effect", "[cli]") {
  const auto dir = scratch_dir("gen_seed");
  const RunResult r = run_vbsim("gen random-triangles --rays 2 --seed 7 --set protocol=pbrt-v4 --set children=1 -o " +
                                (dir / "g").string());
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("warning: option '--seed 7' has no effect") &&
                           Catch::Contains("--set first=N"));
  const RunResult seeded = run_vbsim("gen random-triangles --rays 2 --seed 7 -o " + (dir / "h").string());
  CHECK_THAT(seeded.output, !Catch::Contains("has no effect"));
}
