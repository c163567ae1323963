// Parsing on several threads: a text trace read with parse threads gives the
// same rays, line numbers and errors, in the same order, as with one, also
// after an error (as `vbsim check` reads on); parallel_for rethrows the error
// of the lowest index, whatever the thread count.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "parallel/parallel_for.h"
#include "trace/text_trace_reader.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

/// 10,000 rays (more than two blocks read ahead) with problems scattered
/// over them: malformed lines, a field out of range, a duplicate id, comment
/// and blank lines; the last line lacks its newline.
std::string damaged_trace() {
  std::string text = R"({"format": "vbsim-trace", "version": 1, "scene": "scene.obj"})" "\n";
  for (int i = 0; i < 10000; ++i) {
    if (i == 17 || i == 4095 || i == 4096 || i == 9999) text += "{\"id\":";
    else if (i == 300) text += "# a comment\n\n";
    else if (i == 5000) text += "{\"id\": 4000, \"o\": [0, 0, 0], \"d\": [1, 0, 0]}";
    else if (i == 7000) text += "{\"id\": 7000, \"o\": [0, 0, 0], \"d\": [0, 0, 0]}";
    else text += "{\"id\": " + std::to_string(i) + ", \"o\": [0, 0, " + std::to_string(i) + "], \"d\": [1, 0, 0]}";
    if (i != 9999) text += "\n";
  }
  return text;
}

/// Every ray's id and line, and every error's text, in the order next() gives them.
std::vector<std::string> read_with(const std::string& path, int threads) {
  TextTraceReader reader(path);
  reader.set_parse_threads(threads);
  std::vector<std::string> seen;
  TraceRay ray;
  for (;;) {
    try {
      if (!reader.next(ray)) break;
      seen.push_back(std::to_string(ray.id) + "@" + std::to_string(reader.line_number()));
    } catch (const TraceError& e) {
      seen.push_back(e.what());
    }
  }
  seen.push_back("end@" + std::to_string(reader.line_number()));
  return seen;
}

}  // namespace

TEST_CASE("a text trace parsed on several threads gives one thread's rays and errors", "[trace][threads]") {
  TempDir dir("parse-threads");
  const std::string path = dir.file("t.jsonl");
  write_file(path, damaged_trace());
  const std::vector<std::string> one = read_with(path, 1);
  REQUIRE(one.size() == 10000);  // 9,999 lines of rays (ray 300 gave way to three lines without one), the end
  CHECK_THAT(one[17], Catch::Contains("t.jsonl:19:"));
  CHECK(one[400] == "401@405");
  CHECK_THAT(one[4999], Catch::Contains("t.jsonl:5004: field 'id'"));
  CHECK(one.back() == "end@10003");
  for (int threads : {2, 3, 7}) {
    INFO("threads " << threads);
    CHECK(read_with(path, threads) == one);
  }
}

TEST_CASE("parallel_for rethrows the lowest index's error", "[threads]") {
  for (int threads : {1, 2, 3, 7}) {
    INFO("threads " << threads);
    std::vector<int> done(1000, 0);
    try {
      parallel_for(done.size(), threads, [&](size_t i) {
        if (i % 100 == 37) throw std::runtime_error("job " + std::to_string(i));
        done[i] = 1;
      });
      FAIL("no error");
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()) == "job 37");
    }
    for (size_t i = 0; i < 37; ++i) CHECK(done[i] == 1);
  }
}
