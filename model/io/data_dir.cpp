#include "io/data_dir.h"

#include <cstdlib>

namespace vbsim {

namespace {

std::string& registered_dir() {
  static std::string dir;  // a function-local static: safe to set from another static initializer
  return dir;
}

/// `sub` of the installed layout's data directory, or "" when neither the
/// environment nor set_data_dir() names one.
std::string installed(const char* sub) {
  const char* env = std::getenv("VBSIM_DATA_DIR");
  if (env && *env) return std::string(env) + "/" + sub;
  if (!registered_dir().empty()) return registered_dir() + "/" + sub;
  return {};
}

}  // namespace

bool set_data_dir(const std::string& dir) {
  registered_dir() = dir;
  return true;
}

std::string presets_dir() {
  const std::string dir = installed("presets");
  return dir.empty() ? std::string(VBSIM_PRESETS_DIR) : dir;
}

std::string tech_dir() {
  const std::string dir = installed("tech");
  return dir.empty() ? std::string(VBSIM_TECH_DIR) : dir;
}

}  // namespace vbsim
