// The bit pattern of a float32 and back (a memcpy, the defined way to
// reinterpret): for steps to neighbouring floats and integer ulp offsets.
#pragma once
#include <cstdint>
#include <cstring>

namespace vbsim {

inline uint32_t float_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

inline float bits_float(uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

}  // namespace vbsim
