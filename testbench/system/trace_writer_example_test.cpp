// The C++ writer example of docs/trace-format.md, compiled on its own with
// nothing but the standard library and model/include/vbsim/trace_writer.hpp, run,
// and its trace checked, scored by the oracle and replayed.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <regex>

#include "run_vbsim.h"

using namespace vbsim::test;

namespace {

/// The code block after `<!-- example: cpp writer -->` in docs/trace-format.md.
std::string doc_example() {
  const std::string doc = read_file(source_dir() + "/docs/trace-format.md");
  const std::string marker = "<!-- example: cpp writer -->";
  const std::size_t at = doc.find(marker);
  REQUIRE(at != std::string::npos);
  const std::size_t start = doc.find('\n', doc.find("```cpp", at)) + 1;
  return doc.substr(start, doc.find("```", start) - start);
}

int run(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("the documented C++ writer example compiles with the standard library alone and replays",
          "[writer][cli]") {
  const auto dir = scratch_dir("cpp_writer_example");
  const std::string code = doc_example();
  CHECK(std::count(code.begin(), code.end(), '\n') <= 12);
  write_file(dir / "example.cpp", code);
  std::filesystem::create_symlink(source_dir() + "/traces/bunny/bunny.obj", dir / "bunny.obj");
  // -nostdinc++ is not used: the point is that no include path but model/include/ and no library is needed.
  const std::string compile = std::string(VBSIM_CXX_COMPILER) + " -std=c++17 -Wall -Wextra -Werror -pedantic -I" +
                              source_dir() + "/model/include " + (dir / "example.cpp").string() + " -o " +
                              (dir / "example").string() + " 2>&1";
  REQUIRE(run(compile) == 0);
  REQUIRE(run("cd " + dir.string() + " && ./example") == 0);
  const std::string trace = (dir / "example.jsonl").string();
  RunResult r = run_vbsim("check " + trace);
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("2 rays, 0 errors, 2 warnings (missing_expect 2)"));
  REQUIRE(run_vbsim("oracle " + trace + " -o " + (dir / "scored.jsonl").string()).exit_code == 0);
  r = run_vbsim("check --strict " + (dir / "scored.jsonl").string());
  CHECK(r.exit_code == 0);
  r = run_vbsim("replay " + (dir / "scored.jsonl").string() + " --method validity-bit");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("2"));
}
