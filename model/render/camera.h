// Pinhole camera of `vbsim render`: an eye, a target and a vertical field of
// view; primary rays go through pixel centres. By default it frames the scene's
// bounding sphere from a fixed oblique direction, so any scene, near the origin
// or far from it, fills the image.
#pragma once
#include <optional>

#include "datapath/vec3.h"
#include "scene/scene.h"

namespace vbsim {

struct CameraSpec {
  std::optional<Vec3f> eye;     ///< default: outside the bounds along kDefaultViewDirection
  std::optional<Vec3f> target;  ///< default: centre of the bounds
  float vertical_fov_deg = 40.0f;
};

/// Direction from the target towards the default eye (right, above, in front).
constexpr Vec3f kDefaultViewDirection{0.35f, 0.6f, 1.0f};

class PinholeCamera {
 public:
  /// Camera for a `width` x `height` image of a scene with `bounds`. The
  /// frame is computed in double and rounded to float32 once. Throws
  /// std::invalid_argument when eye and target coincide or the fov is not in (0, 180).
  PinholeCamera(const CameraSpec& spec, const Bounds3f& bounds, int width, int height);

  /// Ray direction (not unit length) through the centre of pixel (x, y);
  /// y = 0 is the top row.
  Vec3f direction(int x, int y) const;
  /// Ray direction through the image point (px, py) in pixel units: pixel
  /// (x, y) covers [x, x + 1) x [y, y + 1).
  Vec3f direction_at(float px, float py) const;
  Vec3f eye() const { return eye_; }

 private:
  Vec3f eye_, forward_, right_, up_;  // right_ and up_ span the image plane at distance 1
  int width_, height_;
};

}  // namespace vbsim
