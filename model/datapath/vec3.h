// Vec3f: the float32 3-vector every datapath unit computes with.
// Plain aggregate, no hidden state; operations round exactly as IEEE single
// precision does (the build disables FMA contraction).
#pragma once
#include <cmath>

namespace vbsim {

struct Vec3f {
  float x = 0, y = 0, z = 0;

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

constexpr Vec3f operator+(Vec3f a, Vec3f b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3f operator-(Vec3f a, Vec3f b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3f operator-(Vec3f a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3f operator*(float s, Vec3f a) { return {s * a.x, s * a.y, s * a.z}; }
constexpr Vec3f operator*(Vec3f a, float s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr bool operator==(Vec3f a, Vec3f b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
constexpr bool operator!=(Vec3f a, Vec3f b) { return !(a == b); }

constexpr float dot(Vec3f a, Vec3f b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3f cross(Vec3f a, Vec3f b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3f a) { return std::sqrt(dot(a, a)); }
inline Vec3f normalize(Vec3f a) { return (1.0f / length(a)) * a; }
inline Vec3f abs(Vec3f a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
inline bool is_finite(Vec3f a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
/// Index of the component with the largest magnitude (0, 1 or 2).
inline int max_dimension(Vec3f a) {
  const Vec3f m = abs(a);
  // x > y ? (x > z ? 0 : 2) : (y > z ? 1 : 2), as selects rather than branches
  const bool x_over_y = m.x > m.y;
  const int xy = x_over_y ? 0 : 1;
  const float m_xy = x_over_y ? m.x : m.y;
  return m_xy > m.z ? xy : 2;
}

}  // namespace vbsim
