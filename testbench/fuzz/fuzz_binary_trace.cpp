// Fuzz target: the binary trace reader (.vbt) on any bytes (checks in fuzz_checks.h).
#include "fuzz_checks.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vbsim::fuzz::check_binary_trace(vbsim::fuzz::input_file(data, size, ".vbt"));
  return 0;
}
