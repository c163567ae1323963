#include "render/camera.h"

#include <cmath>
#include <stdexcept>

#include "datapath/dvec3.h"

namespace vbsim {

PinholeCamera::PinholeCamera(const CameraSpec& spec, const Bounds3f& bounds, int width, int height)
    : width_(width), height_(height) {
  if (!(spec.vertical_fov_deg > 0.0f && spec.vertical_fov_deg < 180.0f))
    throw std::invalid_argument("camera: field of view must be in (0, 180) degrees");
  const double half_v = 0.5 * spec.vertical_fov_deg * M_PI / 180.0;
  const double tan_v = std::tan(half_v);
  const double aspect = double(width) / double(height);
  const double tan_h = tan_v * aspect;

  const bool empty = !(bounds.lo.x <= bounds.hi.x);
  const DVec3 lo = empty ? DVec3{-1, -1, -1} : to_dvec(bounds.lo);
  const DVec3 hi = empty ? DVec3{1, 1, 1} : to_dvec(bounds.hi);
  const DVec3 centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * std::sqrt(ddot(hi - lo, hi - lo)), 1e-30);
  const DVec3 target = spec.target ? to_dvec(*spec.target) : centre;
  DVec3 eye;
  if (spec.eye) {
    eye = to_dvec(*spec.eye);
  } else {
    // Far enough that the bounding sphere's central disc fills the narrower
    // field of view (a little of a scene's corners may leave the frame).
    eye = target + (radius / std::min(tan_v, tan_h)) * dunit(to_dvec(kDefaultViewDirection));
  }
  const DVec3 f = target - eye;
  if (!(ddot(f, f) > 0.0)) throw std::invalid_argument("camera: eye and target coincide");
  const DVec3 fwd = dunit(f);
  DVec3 world_up{0, 1, 0};
  if (std::fabs(ddot(fwd, world_up)) > 0.999) world_up = {0, 0, -1};
  const DVec3 right = dunit(dcross(fwd, world_up));
  const DVec3 up = dcross(right, fwd);
  eye_ = to_vec3f(eye);
  forward_ = to_vec3f(fwd);
  right_ = to_vec3f(tan_h * right);
  up_ = to_vec3f(tan_v * up);
}

Vec3f PinholeCamera::direction(int x, int y) const {
  const float sx = 2.0f * (float(x) + 0.5f) / float(width_) - 1.0f;
  const float sy = 1.0f - 2.0f * (float(y) + 0.5f) / float(height_);
  return forward_ + sx * right_ + sy * up_;
}

Vec3f PinholeCamera::direction_at(float px, float py) const {
  const float sx = 2.0f * px / float(width_) - 1.0f;
  const float sy = 1.0f - 2.0f * py / float(height_);
  return forward_ + sx * right_ + sy * up_;
}

}  // namespace vbsim
