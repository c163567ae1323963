#include "render/float_list.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace vbsim {

bool parse_float_list(const std::string& text, size_t count, std::vector<float>& out) {
  out.clear();
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    if (part.empty()) return false;
    char* end = nullptr;
    const float v = std::strtof(part.c_str(), &end);
    if (*end != '\0' || !std::isfinite(v)) return false;
    out.push_back(v);
  }
  // A trailing comma leaves no empty part for getline: reject it here.
  return out.size() == count && !text.empty() && text.back() != ',';
}

}  // namespace vbsim
