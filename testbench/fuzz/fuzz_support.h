// Shared by the libFuzzer targets: the readers take file paths, so each input
// is written to one scratch file per process (in /dev/shm when it exists).
// What each target checks: fuzz_checks.h.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace vbsim::fuzz {

/// Writes the input to the scratch file with this suffix (".ply": the
/// scene loader picks the format by it) and returns its path.
std::string input_file(const uint8_t* data, size_t size, const char* suffix);

}  // namespace vbsim::fuzz
