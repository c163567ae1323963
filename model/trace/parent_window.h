// The parent window: how many rays back a child's parent may lie in a trace.
// One window for every reader of a run: the consistency checks
// (ParentOrderCheck, `vbsim check`) look for a parent as far back as the
// replays keep parent rays (ParentRayStore), so that a trace `check` passes
// is one a replay can follow; `--parent-window` sets both.
#pragma once
#include <cstdint>

namespace vbsim {

/// Default window: a child's parent must be among the 131072 rays before it.
/// Renderers that trace depth-first (every vbsim generator) put a parent a
/// few rays before its children.
constexpr int64_t kDefaultParentWindow = int64_t{1} << 17;
/// Largest window (2^31 - 1 rays): slot indices are 32-bit.
constexpr int64_t kMaxParentWindow = (int64_t{1} << 31) - 1;

}  // namespace vbsim
