// ParentRays: id -> (o, d) of the trace rays seen so far, so that a child can
// find its parent ray (intended origins, ray-equation hit points).
#pragma once
#include <cstdint>
#include <unordered_map>
#include <utility>

#include "datapath/vec3.h"

namespace vbsim {

using ParentRays = std::unordered_map<int64_t, std::pair<Vec3f, Vec3f>>;

}  // namespace vbsim
