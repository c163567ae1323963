#include "render/camera.h"

#include <cmath>
#include <stdexcept>

namespace vbsim {

namespace {

struct D3 {
  double x, y, z;
};
D3 to_d(Vec3f v) { return {v.x, v.y, v.z}; }
Vec3f to_f(D3 v) { return {float(v.x), float(v.y), float(v.z)}; }
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 add(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 scale(double s, D3 a) { return {s * a.x, s * a.y, s * a.z}; }
double ddot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 dcross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 unit(D3 a) { return scale(1.0 / std::sqrt(ddot(a, a)), a); }

}  // namespace

PinholeCamera::PinholeCamera(const CameraSpec& spec, const Bounds3f& bounds, int width, int height)
    : width_(width), height_(height) {
  if (!(spec.vertical_fov_deg > 0.0f && spec.vertical_fov_deg < 180.0f))
    throw std::invalid_argument("camera: field of view must be in (0, 180) degrees");
  const double half_v = 0.5 * spec.vertical_fov_deg * M_PI / 180.0;
  const double tan_v = std::tan(half_v);
  const double aspect = double(width) / double(height);
  const double tan_h = tan_v * aspect;

  const bool empty = !(bounds.lo.x <= bounds.hi.x);
  const D3 lo = empty ? D3{-1, -1, -1} : to_d(bounds.lo), hi = empty ? D3{1, 1, 1} : to_d(bounds.hi);
  const D3 centre = scale(0.5, add(lo, hi));
  const double radius = std::max(0.5 * std::sqrt(ddot(sub(hi, lo), sub(hi, lo))), 1e-30);
  const D3 target = spec.target ? to_d(*spec.target) : centre;
  D3 eye;
  if (spec.eye) {
    eye = to_d(*spec.eye);
  } else {
    // Far enough that the bounding sphere's central disc fills the narrower
    // field of view (a little of a scene's corners may leave the frame).
    eye = add(target, scale(radius / std::min(tan_v, tan_h), unit(to_d(kDefaultViewDirection))));
  }
  const D3 f = sub(target, eye);
  if (!(ddot(f, f) > 0.0)) throw std::invalid_argument("camera: eye and target coincide");
  const D3 fwd = unit(f);
  D3 world_up{0, 1, 0};
  if (std::fabs(ddot(fwd, world_up)) > 0.999) world_up = {0, 0, -1};
  const D3 right = unit(dcross(fwd, world_up));
  const D3 up = dcross(right, fwd);
  eye_ = to_f(eye);
  forward_ = to_f(fwd);
  right_ = to_f(scale(tan_h, right));
  up_ = to_f(scale(tan_v, up));
}

Vec3f PinholeCamera::direction(int x, int y) const {
  const float sx = 2.0f * (float(x) + 0.5f) / float(width_) - 1.0f;
  const float sy = 1.0f - 2.0f * (float(y) + 0.5f) / float(height_);
  return forward_ + sx * right_ + sy * up_;
}

}  // namespace vbsim
