#include "scene/scene_transform.h"

#include <cmath>

#include <fmt/format.h>

#include "scene/scene.h"

namespace vbsim {

SceneTransform::SceneTransform(const std::array<float, 16>& m, const std::string& source) : m_(m) {
  for (int i = 0; i < 16; ++i)
    if (!std::isfinite(m[i]))
      throw SceneError(fmt::format("scene '{}': transform[{}] is not finite ({})", source, i, m[i]));
  if (m[12] != 0.0f || m[13] != 0.0f || m[14] != 0.0f || m[15] != 1.0f)
    throw SceneError(fmt::format(
        "scene '{}': transform row 3 must be 0 0 0 1 (affine), got {} {} {} {}", source, m[12], m[13],
        m[14], m[15]));

  // (A^-1)^T = cofactor(A) / det(A).
  auto a = [&](int r, int c) { return static_cast<double>(m[4 * r + c]); };
  double cof[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      cof[r][c] = a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1);
    }
  const double det = a(0, 0) * cof[0][0] + a(0, 1) * cof[0][1] + a(0, 2) * cof[0][2];
  invertible_ = det != 0.0 && std::isfinite(det);
  if (invertible_)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) normal_matrix_[r][c] = cof[r][c] / det;
}

Vec3f SceneTransform::point(Vec3f p) const {
  auto row = [&](int r) { return m_[4 * r] * p.x + m_[4 * r + 1] * p.y + m_[4 * r + 2] * p.z + m_[4 * r + 3]; };
  return {row(0), row(1), row(2)};
}

Vec3f SceneTransform::normal(Vec3f n) const {
  auto row = [&](int r) {
    return static_cast<float>(normal_matrix_[r][0] * n.x + normal_matrix_[r][1] * n.y +
                              normal_matrix_[r][2] * n.z);
  };
  return {row(0), row(1), row(2)};
}

}  // namespace vbsim
