// An instance's transform as rtcSetGeometryTransform takes it, in any of its
// formats, as the row-major 3x4 matrix the capture's files hold: world =
// M[0..2][0..2] * object + M[0..2][3]. Shared by the capture shim and vbsim
// (standard library only).
#pragma once
#include <cstdint>

namespace vbsim::capture {

/// RTCFormat values of the transform layouts (embree3/rtcore_common.h).
constexpr uint32_t kFormatFloat3x4RowMajor = 0x9134;
constexpr uint32_t kFormatFloat4x4RowMajor = 0x9144;
constexpr uint32_t kFormatFloat3x4ColumnMajor = 0x9234;
constexpr uint32_t kFormatFloat4x4ColumnMajor = 0x9244;

/// Fills `out` (row-major 3x4) from `in` in `format`; false for another format.
inline bool instance_transform_row_major(uint32_t format, const float* in, float out[12]) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      switch (format) {
        case kFormatFloat3x4RowMajor:
        case kFormatFloat4x4RowMajor: out[r * 4 + c] = in[r * 4 + c]; break;
        case kFormatFloat3x4ColumnMajor: out[r * 4 + c] = in[c * 3 + r]; break;
        case kFormatFloat4x4ColumnMajor: out[r * 4 + c] = in[c * 4 + r]; break;
        default: return false;
      }
    }
  return true;
}

}  // namespace vbsim::capture
