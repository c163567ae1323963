// Fuzz target: the scene loading path for OBJ files on any bytes (checks in fuzz_checks.h).
#include "fuzz_checks.h"
#include "fuzz_support.h"
#include "structured_mutator.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vbsim::fuzz::check_scene(vbsim::fuzz::input_file(data, size, ".obj"));
  return 0;
}

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t max_size);

// Structure-aware mutations beside libFuzzer's byte mutations (structured_mutator.h).
extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t max_size, unsigned int seed) {
  return vbsim::fuzz::structured_mutate(vbsim::fuzz::InputFormat::Obj, data, size, max_size, seed, LLVMFuzzerMutate);
}
