// SceneTransform: the trace header's optional row-major 4x4 transform, as a
// renderer's instance transform applies it (trace spec, "Scene").
#pragma once
#include <array>
#include <string>

#include "datapath/vec3.h"

namespace vbsim {

class SceneTransform {
 public:
  /// Validates `m` (16 finite numbers, last row 0 0 0 1); throws SceneError
  /// naming `source` otherwise.
  SceneTransform(const std::array<float, 16>& m, const std::string& source);

  /// Vertex: x' = m0*x + m1*y + m2*z + m3 (and rows 1, 2 likewise), evaluated
  /// left to right in float32 without FMA: ((m0*x + m1*y) + m2*z) + m3.
  Vec3f point(Vec3f p) const;

  /// Normal: n' = (A^-1)^T n with A the upper 3x3, computed in double and rounded
  /// to float32 once; not renormalised. Precondition: invertible().
  Vec3f normal(Vec3f n) const;

  /// True when the upper 3x3 has a non-zero determinant (in double).
  bool invertible() const { return invertible_; }

 private:
  std::array<float, 16> m_;
  double normal_matrix_[3][3] = {};  // (A^-1)^T, row-major
  bool invertible_ = false;
};

}  // namespace vbsim
