// Fuzz target: the text trace reader (.jsonl) on any bytes (checks in fuzz_checks.h).
#include "fuzz_checks.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vbsim::fuzz::check_text_trace(vbsim::fuzz::input_file(data, size, ".jsonl"));
  return 0;
}
