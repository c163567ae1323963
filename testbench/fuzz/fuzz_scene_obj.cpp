// Fuzz target: the scene loading path for OBJ files on any bytes (checks in fuzz_checks.h).
#include "fuzz_checks.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vbsim::fuzz::check_scene(vbsim::fuzz::input_file(data, size, ".obj"));
  return 0;
}
