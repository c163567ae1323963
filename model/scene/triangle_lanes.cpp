#include "scene/triangle_lanes.h"

#include "scene/bvh.h"

namespace vbsim {

void TriangleLanes::fill(const BvhTriangle* tris, size_t count) {
  count_ = count;
  stride_ = count + kPadding;
  data_.assign(9 * stride_, 0.0f);  // padding lanes: a degenerate triangle at the origin
  for (size_t i = 0; i < count; ++i) {
    const Vec3f v[3] = {tris[i].tri.v0, tris[i].tri.v1, tris[i].tri.v2};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) data_[static_cast<size_t>(3 * k + a) * stride_ + i] = v[k][a];
  }
}

}  // namespace vbsim
