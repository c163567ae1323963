#include "render/render_colours.h"

#include <algorithm>
#include <cmath>

namespace vbsim {

Rgb8 to_rgb8(Vec3f c) {
  Rgb8 out{};
  for (int i = 0; i < 3; ++i)
    out[i] = static_cast<uint8_t>(std::lround(std::clamp(c[i], 0.0f, 1.0f) * 255.0f));
  return out;
}

uint8_t grey_of(const Rgb8& c) {
  return static_cast<uint8_t>((77u * c[0] + 150u * c[1] + 29u * c[2]) >> 8);
}

}  // namespace vbsim
