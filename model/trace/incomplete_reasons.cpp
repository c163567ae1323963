#include "trace/incomplete_reasons.h"

namespace vbsim {

namespace {

const char* const kNames[kIncompleteReasonCount] = {"instance", "quad",  "grid",        "subdivision",    "curve",
                                                    "point",    "user",  "motion_blur", "other_geometry", "filter",
                                                    "mask",     "unlinked"};

}  // namespace

const char* incomplete_reason_name(int index) {
  return index >= 0 && index < kIncompleteReasonCount ? kNames[index] : "unknown";
}

bool parse_incomplete_reason(const std::string& name, uint32_t& bit) {
  for (int k = 0; k < kIncompleteReasonCount; ++k)
    if (name == kNames[k]) {
      bit = 1u << k;
      return true;
    }
  return false;
}

std::string incomplete_reasons_text(uint32_t bits) {
  std::string s;
  for (int k = 0; k < kIncompleteReasonCount; ++k)
    if (bits & (1u << k)) s += (s.empty() ? "" : ", ") + std::string(kNames[k]);
  return s;
}

std::string incomplete_reason_names() { return incomplete_reasons_text(kIncompleteKnownBits); }

}  // namespace vbsim
