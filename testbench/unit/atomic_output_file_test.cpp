// AtomicOutputFile and check_output_paths: a file appears under its name only
// when complete, an existing file survives a failed write, write errors are
// reported, and an output naming an input is refused.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/atomic_output_file.h"
#include "io/output_paths.h"

using namespace vbsim;
namespace fs = std::filesystem;

namespace {

struct Dir {
  fs::path path = fs::temp_directory_path() / ("vbsim_atomic_" + std::to_string(::getpid()));
  Dir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Dir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
  size_t entries() const { return static_cast<size_t>(std::distance(fs::directory_iterator(path), {})); }
};

std::string read(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_CASE("atomic output: the file appears only on commit", "[outputs]") {
  Dir d;
  const std::string out = d.file("o.txt");
  {
    AtomicOutputFile f(out);
    f.stream() << "hello\n";
    f.stream().flush();
    CHECK_FALSE(fs::exists(out));
    CHECK(read(f.temp_path()) == "hello\n");
    f.commit();
    f.commit();  // a second commit does nothing
    CHECK(f.committed());
  }
  CHECK(read(out) == "hello\n");
  CHECK(d.entries() == 1);
}

TEST_CASE("atomic output: without commit the old file stays and nothing is left", "[outputs]") {
  Dir d;
  const std::string out = d.file("o.txt");
  std::ofstream(out) << "old\n";
  {
    AtomicOutputFile f(out);
    f.stream() << "new, unfinished";
  }
  CHECK(read(out) == "old\n");
  CHECK(d.entries() == 1);
  {
    AtomicOutputFile f(out);
    f.stream() << "new\n";
    f.discard();
    CHECK_THROWS_AS(f.commit(), OutputError);
  }
  CHECK(read(out) == "old\n");
}

TEST_CASE("atomic output: errors name the file", "[outputs]") {
  Dir d;
  CHECK_THROWS_WITH(AtomicOutputFile(d.file("no/such/dir/o.txt")),
                    Catch::StartsWith(d.file("no/such/dir/o.txt") + ": cannot create"));
  if (fs::exists("/dev/full")) {
    AtomicOutputFile full("/dev/full");
    full.stream() << std::string(1 << 16, 'x');
    CHECK_THROWS_WITH(full.commit(), Catch::StartsWith("/dev/full: write failed"));
  }
  AtomicOutputFile null("/dev/null");  // not a regular file: written in place
  null.stream() << "discarded";
  CHECK_NOTHROW(null.commit());
  CHECK(fs::exists("/dev/null"));
}

TEST_CASE("atomic output: a symbolic link keeps naming the file it points at", "[outputs]") {
  Dir d;
  std::ofstream(d.file("target.txt")) << "old";
  fs::create_symlink(d.file("target.txt"), d.file("link.txt"));
  write_output_file(d.file("link.txt"), "new", "test output");
  CHECK(fs::is_symlink(d.file("link.txt")));
  CHECK(read(d.file("target.txt")) == "new");
}

TEST_CASE("atomic output: held commits take their names only when committed, in order", "[outputs]") {
  Dir d;
  const std::string a = d.file("a.txt"), b = d.file("b.txt");
  std::ofstream(a) << "old\n";
  hold_output_commits();
  write_output_file(a, "first\n", "test output");
  write_output_file(b, "b\n", "test output");
  write_output_file(a, "second\n", "test output");  // the same name twice: the last commit wins
  CHECK(read(a) == "old\n");
  CHECK_FALSE(fs::exists(b));
  CHECK(d.entries() == 4);  // a and three finished temporaries
  {
    const CommitsAtOnce at_once;  // an output the run reads back
    write_output_file(d.file("c.txt"), "c\n", "test output");
    CHECK(read(d.file("c.txt")) == "c\n");
  }
  commit_held_outputs();
  CHECK(read(a) == "second\n");
  CHECK(read(b) == "b\n");
  CHECK(d.entries() == 3);
  write_output_file(b, "at once\n", "test output");  // no longer held
  CHECK(read(b) == "at once\n");

  hold_output_commits();
  write_output_file(a, "never\n", "test output");
  write_output_file(d.file("d.txt"), "never\n", "test output");
  discard_held_outputs();
  CHECK(read(a) == "second\n");
  CHECK_FALSE(fs::exists(d.file("d.txt")));
  CHECK(d.entries() == 3);
}

TEST_CASE("atomic output: a held output is read back from its temporary until it is committed", "[outputs]") {
  Dir d;
  const std::string a = d.file("a.txt");
  CHECK(finished_output_path(a) == a);
  hold_output_commits();
  write_output_file(a, "first\n", "test output");
  const std::string held = finished_output_path(a);
  CHECK(held != a);
  CHECK(read(held) == "first\n");
  // Rewritten from what was read back (as a VCD gets its provenance comment): the rewrite wins.
  write_output_file(a, "header\n" + read(held), "test output");
  CHECK(read(finished_output_path(a)) == "header\nfirst\n");
  CHECK_FALSE(fs::exists(a));
  commit_held_outputs();
  CHECK(finished_output_path(a) == a);
  CHECK(read(a) == "header\nfirst\n");
  CHECK(d.entries() == 1);
}

TEST_CASE("atomic output: a held output whose directory went away fails to commit, naming it", "[outputs]") {
  Dir d;
  fs::create_directories(d.path / "sub");
  hold_output_commits();
  write_output_file(d.file("sub/x.txt"), "x", "test output");
  write_output_file(d.file("y.txt"), "y", "test output");
  fs::remove_all(d.path / "sub");
  CHECK_THROWS_WITH(commit_held_outputs(), Catch::StartsWith(d.file("sub/x.txt") + ": write failed"));
  CHECK_FALSE(fs::exists(d.file("y.txt")));  // the rest are removed
  CHECK(d.entries() == 0);
}

TEST_CASE("output paths: an output that is an input or another output is refused", "[outputs]") {
  Dir d;
  std::ofstream(d.file("in.jsonl")) << "x";
  fs::create_hard_link(d.file("in.jsonl"), d.file("hard.jsonl"));
  const std::vector<NamedPath> inputs = {{"trace", d.file("in.jsonl")}, {"option '--config'", ""}};
  CHECK_THROWS_WITH(check_output_paths(inputs, {{"option '--hits'", d.file("in.jsonl")}}),
                    Catch::Contains("option '--hits'") && Catch::Contains("also the trace"));
  CHECK_THROWS_AS(check_output_paths(inputs, {{"-o", d.file("hard.jsonl")}}), OutputPathError);
  CHECK_THROWS_AS(check_output_paths(inputs, {{"-o", (d.path / "sub" / ".." / "in.jsonl").string()}}), OutputPathError);
  CHECK_THROWS_WITH(check_output_paths(inputs, {{"--stats", d.file("a.json")}, {"--hits", d.file("a.json")}}),
                    Catch::Contains("also the output of --stats"));
  CHECK_NOTHROW(check_output_paths(inputs, {{"--stats", d.file("a.json")}, {"--hits", d.file("b.json")}, {"--vcd", ""}}));
  CHECK_NOTHROW(check_output_paths(inputs, {{"--stats", "/dev/null"}, {"--hits", "/dev/null"}}));
}
