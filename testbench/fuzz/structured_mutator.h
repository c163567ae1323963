// Structure-aware mutations of the fuzzed formats, beside libFuzzer's byte
// mutations: what a hostile file does to a reader's structure rather than to
// its bytes. Used by the fuzz targets' LLVMFuzzerCustomMutator (scripts/fuzz.sh)
// and, seeded, by the suite (testbench/unit/structured_mutator_test.cpp).
//
// Mutations, one per call, chosen by `seed`:
//   - nesting: a JSON value wrapped in 1 to 100,000 levels of [ ] or {"k": }
//     (JSON formats), up to `max_size`;
//   - extreme numbers: a number replaced by one at or beyond a limit (float32
//     and double overflow and underflow, denormals, int64 bounds, -0, huge
//     exponents);
//   - lying counts: a binary trace's header length, or a PLY element count,
//     set to a value near, beyond or inside the true one;
//   - repeated keys: a "key": value pair of a JSON object written twice;
//   - otherwise the byte mutator given (libFuzzer's LLVMFuzzerMutate).
#pragma once
#include <cstddef>
#include <cstdint>

namespace vbsim::fuzz {

enum class InputFormat { JsonLines, Json, BinaryTrace, Ply, Obj };

/// libFuzzer's LLVMFuzzerMutate, or a stand-in: mutates data[0, size) in place
/// within max_size bytes and returns the new size.
using ByteMutator = size_t (*)(uint8_t* data, size_t size, size_t max_size);

/// Mutates data[0, size) in place (at most max_size bytes) and returns the new size.
size_t structured_mutate(InputFormat format, uint8_t* data, size_t size, size_t max_size, unsigned seed,
                         ByteMutator bytes);

}  // namespace vbsim::fuzz
