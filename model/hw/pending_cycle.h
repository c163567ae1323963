// kPendingCycle: "a cycle no one knows yet". A unit that cannot answer when its
// data will be there (an approximately timed memory behind it) answers this and
// gives the real cycle later through a callback (hw/unit_interfaces.h). It is
// larger than every real cycle, so a line filled at kPendingCycle is in flight
// for every request, and MSHRs held until it sort last.
#pragma once
#include <cstdint>

namespace vbsim::hw {

constexpr uint64_t kPendingCycle = ~uint64_t{0};

}  // namespace vbsim::hw
