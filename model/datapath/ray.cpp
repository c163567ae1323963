#include "datapath/ray.h"

#include <cstring>

namespace vbsim {

namespace {
constexpr const char* kKindNames[kRayKindCount] = {"primary", "reflect", "refract", "diffuse",
                                                   "shadow"};
}

const char* ray_kind_name(RayKind kind) { return kKindNames[static_cast<int>(kind)]; }

bool parse_ray_kind(const char* name, RayKind& out) {
  for (int i = 0; i < kRayKindCount; ++i) {
    if (std::strcmp(name, kKindNames[i]) == 0) {
      out = static_cast<RayKind>(i);
      return true;
    }
  }
  return false;
}

}  // namespace vbsim
