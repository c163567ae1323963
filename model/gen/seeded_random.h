// SeededRandom: the generators' deterministic random source. Same seed, same
// numbers, on every platform (no std:: distributions, whose output is
// implementation-defined).
#pragma once
#include <cmath>
#include <cstdint>
#include <random>

#include "datapath/vec3.h"

namespace vbsim {

class SeededRandom {
 public:
  explicit SeededRandom(uint64_t seed) : eng_(seed) {}
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(eng_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n).
  uint64_t below(uint64_t n) { return static_cast<uint64_t>(uniform() * static_cast<double>(n)); }
  /// Uniform direction on the unit sphere (double precision, rounded to float).
  Vec3f unit_vector() {
    const double z = uniform(-1.0, 1.0), phi = uniform(0.0, 2.0 * M_PI);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
            static_cast<float>(z)};
  }

 private:
  std::mt19937_64 eng_;
};

}  // namespace vbsim
