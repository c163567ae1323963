// Shared by the libFuzzer targets: the readers take file paths, so each input
// is written to one scratch file per process (in /dev/shm when it exists).
// Contract of every target: an input is either read or refused with the
// reader's own error type; any other exception, a crash, a sanitizer report,
// a hang or a broken invariant is a finding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>

namespace vbsim::fuzz {

/// Writes the input to the scratch file with this suffix (".ply": the
/// scene loader picks the format by it) and returns its path.
std::string input_file(const uint8_t* data, size_t size, const char* suffix);

/// A broken invariant: prints `what` and aborts, which libFuzzer reports as a crash.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "vbsim fuzz finding: %s\n", what.c_str());
  std::abort();
}

}  // namespace vbsim::fuzz
