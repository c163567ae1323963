// TriangleLanes: the coordinates of Bvh::tris again, as a structure of arrays
// (one array per vertex and axis), so that a software search loads one
// coordinate of four consecutive triangles (a leaf's) in one vector load, as
// Embree keeps its Triangle4 leaves. A host-side copy for the functional
// search's speed only: the hardware model fetches BvhTriangle records
// (bvh.h), and no modelled byte or cycle depends on this copy.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbsim {

struct BvhTriangle;

class TriangleLanes {
 public:
  /// Lanes a reader may load past the last triangle (the arrays are padded):
  /// a four-lane load that starts at the last one.
  static constexpr size_t kPadding = 3;

  /// Copies the coordinates of `tris[0..count)`.
  void fill(const BvhTriangle* tris, size_t count);
  /// Triangles held: a search uses the lanes only when this equals the tree's
  /// triangle count (a tree put together by hand has none).
  size_t size() const { return count_; }
  /// Coordinate `axis` (0 x, 1 y, 2 z) of vertex `vertex` (0, 1, 2) of every
  /// triangle, in Bvh::tris order; readable up to size() + kPadding.
  const float* coord(int vertex, int axis) const { return data_.data() + static_cast<size_t>(3 * vertex + axis) * stride_; }
  /// Floats from one axis's array to the next axis's (coord(v, a + 1) - coord(v, a)).
  size_t axis_stride() const { return stride_; }
  /// Floats from one vertex's array to the next vertex's (coord(v + 1, a) - coord(v, a)).
  size_t vertex_stride() const { return 3 * stride_; }

 private:
  std::vector<float> data_;
  size_t stride_ = 0;
  size_t count_ = 0;
};

}  // namespace vbsim
