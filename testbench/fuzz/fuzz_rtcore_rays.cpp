// Fuzz target: the rtcore-systemc ray import on any bytes (checks in fuzz_checks.h).
#include "fuzz_checks.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vbsim::fuzz::check_rtcore_rays(vbsim::fuzz::input_file(data, size, ".bin"));
  return 0;
}
