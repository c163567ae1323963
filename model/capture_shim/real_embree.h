// The functions behind the shim's interposed ones, each looked up once on
// first use: the application's Embree 3 for the Embree hooks (where it is
// found: embree_library.h) and the C library for the exec hooks. Neither
// lookup returns without a function: when there is none the capture is
// refused (refuse_capture), never aborted.
#pragma once
#include <embree3/rtcore.h>

#include "embree_library.h"

/// Declares `real` as the application's own Embree function `name`, resolved on first use.
#define VBSIM_REAL(name) \
  static const auto real = reinterpret_cast<decltype(&::name)>(::vbsim::shim::embree_function(#name))

/// Declares `real` as the C library's `name` (the next definition after the shim's), resolved on first use.
#define VBSIM_REAL_LIBC(name) \
  static const auto real = reinterpret_cast<decltype(&::name)>(::vbsim::shim::next_function(#name))
