#include "render/render_random.h"

#include <algorithm>
#include <cmath>

namespace vbsim {

namespace {

/// SplitMix64's finaliser: a bijective mix of 64 bits.
uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

constexpr float kTwoPi = 6.28318530717958647692f;

}  // namespace

RenderRandom::RenderRandom(uint64_t seed, uint32_t pixel, uint32_t sample)
    : key_(mix64(seed ^ mix64((uint64_t{pixel} << 32) | sample))) {}

float RenderRandom::uniform(uint32_t bounce, uint32_t dim) const {
  const uint64_t h = mix64(key_ ^ mix64((uint64_t{bounce} << 8) | dim));
  return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
}

Vec3f RenderRandom::cosine_direction(Vec3f n, uint32_t bounce) const {
  const float u1 = uniform(bounce, 2), u2 = uniform(bounce, 3);
  const float r = std::sqrt(u1), phi = kTwoPi * u2;
  const float lx = r * std::cos(phi), ly = r * std::sin(phi), lz = std::sqrt(std::max(0.0f, 1.0f - u1));
  // An orthonormal basis about n without a branch on its direction (Duff et al., JCGT 2017).
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  const Vec3f t1{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
  const Vec3f t2{b, sign + n.y * n.y * a, -n.y};
  return lx * t1 + ly * t2 + lz * n;
}

}  // namespace vbsim
