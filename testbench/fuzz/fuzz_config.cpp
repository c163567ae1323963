// Fuzz target: the configuration reader on any bytes (checks in fuzz_checks.h).
#include "fuzz_checks.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vbsim::fuzz::check_config(vbsim::fuzz::input_file(data, size, ".json"));
  return 0;
}
