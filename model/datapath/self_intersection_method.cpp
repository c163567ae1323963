#include "datapath/self_intersection_method.h"

#include <sstream>

namespace vbsim {

const std::vector<std::string>& method_names() {
  static const std::vector<std::string> names = {
      "none", "tmin", "primid", "offset-normal", "offset-direction", "offset-adaptive",
      "offset-errbound", "validity-bit", "sign-only", "shading-position",
      "shading-position-always", "reverse-shadow"};
  return names;
}

std::string SelfIntersectionMethod::name() const {
  std::vector<std::string> parts;
  if (tmin) parts.push_back("tmin");
  if (primid) parts.push_back("primid");
  if (offset_normal) parts.push_back("offset-normal");
  if (offset_direction) parts.push_back("offset-direction");
  if (offset_adaptive) parts.push_back("offset-adaptive");
  if (offset_errbound) parts.push_back("offset-errbound");
  if (validity_bit)
    parts.push_back(avoidance.policy == AvoidancePolicy::SignOnly ? "sign-only" : "validity-bit");
  if (shading_position) parts.push_back("shading-position");
  if (shading_position_always) parts.push_back("shading-position-always");
  if (reverse_shadow) parts.push_back("reverse-shadow");
  if (parts.empty()) return "none";
  std::string out = parts[0];
  for (size_t i = 1; i < parts.size(); ++i) out += "+" + parts[i];
  return out;
}

int SelfIntersectionMethod::bits_per_ray() const {
  int bits = kBaseRayBits;
  if (validity_bit) bits += 1;
  if (primid) bits += 32;
  return bits;
}

bool parse_method(const std::string& spec, SelfIntersectionMethod& m, std::string& error) {
  std::stringstream in(spec);
  std::string part;
  bool any = false;
  while (std::getline(in, part, '+')) {
    any = true;
    if (part == "none") continue;
    else if (part == "tmin") m.tmin = true;
    else if (part == "primid") m.primid = true;
    else if (part == "offset-normal") m.offset_normal = true;
    else if (part == "offset-direction") m.offset_direction = true;
    else if (part == "offset-adaptive") m.offset_adaptive = true;
    else if (part == "offset-errbound") m.offset_errbound = true;
    else if (part == "validity-bit") {
      m.validity_bit = true;
      if (m.avoidance.policy == AvoidancePolicy::SignOnly) m.avoidance.policy = AvoidancePolicy::All;
    } else if (part == "sign-only") {
      m.validity_bit = true;
      m.avoidance.policy = AvoidancePolicy::SignOnly;
    } else if (part == "shading-position") m.shading_position = true;
    else if (part == "shading-position-always") m.shading_position_always = true;
    else if (part == "reverse-shadow") m.reverse_shadow = true;
    else {
      error = "unknown method '" + part + "' in '" + spec + "'";
      return false;
    }
  }
  if (!any) {
    error = "empty method name";
    return false;
  }
  return true;
}

}  // namespace vbsim
