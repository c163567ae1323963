// The temporaries of killed runs ("NAME.partial-PID-N" whose PID is gone) are
// removed before NAME is written again; a running process's stay.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/atomic_output_file.h"
#include "io/stale_temporaries.h"

using namespace vbsim;
namespace fs = std::filesystem;

namespace {

long gone_pid() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  return child;
}

}  // namespace

TEST_CASE("stale temporaries: names are read exactly", "[outputs]") {
  long pid = 0;
  CHECK(parse_temporary_name("s.json.partial-123-4", "s.json", pid));
  CHECK(pid == 123);
  CHECK_FALSE(parse_temporary_name("s.json.partial-123", "s.json", pid));
  CHECK_FALSE(parse_temporary_name("s.json.partial-12a-4", "s.json", pid));
  CHECK_FALSE(parse_temporary_name("s.json.partial-123-", "s.json", pid));
  CHECK_FALSE(parse_temporary_name("t.json.partial-123-4", "s.json", pid));
  CHECK_FALSE(parse_temporary_name("xs.json.partial-123-4", "s.json", pid));
  CHECK_FALSE(parse_temporary_name("s.json", "s.json", pid));
  CHECK(process_running(::getpid()));
  CHECK_FALSE(process_running(gone_pid()));
}

TEST_CASE("stale temporaries: writing an output removes those of its name whose process is gone", "[outputs]") {
  const fs::path dir = fs::temp_directory_path() / ("vbsim_stale_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string dead = std::to_string(gone_pid()), alive = std::to_string(::getpid());
  std::ofstream(dir / ("o.txt.partial-" + dead + "-0")) << "killed";
  std::ofstream(dir / ("o.txt.partial-" + alive + "-99")) << "running";
  std::ofstream(dir / ("other.txt.partial-" + dead + "-0")) << "another name's";
  fs::create_directories(dir / ("raw.partial-" + dead + "-0"));
  write_output_file((dir / "o.txt").string(), "whole", "test output");
  CHECK_FALSE(fs::exists(dir / ("o.txt.partial-" + dead + "-0")));
  CHECK(fs::exists(dir / ("o.txt.partial-" + alive + "-99")));
  CHECK(fs::exists(dir / ("other.txt.partial-" + dead + "-0")));  // written by nothing here
  CHECK(remove_stale_temporaries((dir / "raw").string()) == 1);   // a directory too
  CHECK_FALSE(fs::exists(dir / ("raw.partial-" + dead + "-0")));
  fs::remove_all(dir);
}
