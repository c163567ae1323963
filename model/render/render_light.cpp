#include "render/render_light.h"

#include <fmt/format.h>

#include "render/float_list.h"

namespace vbsim {

bool parse_render_light(const std::string& text, RenderLight& light, std::string& error) {
  const auto colon = text.find(':');
  const std::string kind = colon == std::string::npos ? "" : text.substr(0, colon);
  RenderLight l;
  if (kind == "point") {
    l.kind = RenderLight::Kind::Point;
  } else if (kind == "dir") {
    l.kind = RenderLight::Kind::Directional;
  } else {
    error = fmt::format("'{}': expected point:X,Y,Z or dir:X,Y,Z", text);
    return false;
  }
  std::vector<float> xyz;
  if (!parse_float_list(text.substr(colon + 1), 3, xyz)) {
    error = fmt::format("'{}': expected three finite numbers after '{}:'", text, kind);
    return false;
  }
  l.value = {xyz[0], xyz[1], xyz[2]};
  if (l.kind == RenderLight::Kind::Directional && l.value == Vec3f{0, 0, 0}) {
    error = fmt::format("'{}': the direction must not be zero", text);
    return false;
  }
  light = l;
  return true;
}

std::string render_light_name(const RenderLight& light) {
  return fmt::format("{}:{},{},{}", light.kind == RenderLight::Kind::Point ? "point" : "dir",
                     light.value.x, light.value.y, light.value.z);
}

}  // namespace vbsim
