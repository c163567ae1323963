// Comma-separated lists of finite numbers in command-line values
// ("1,2.5,-3"), as the render options take them.
#pragma once
#include <string>
#include <vector>

namespace vbsim {

/// Parses exactly `count` finite comma-separated float32 numbers into `out`.
/// Returns false (leaving `out` unspecified) on anything else.
bool parse_float_list(const std::string& text, size_t count, std::vector<float>& out);

}  // namespace vbsim
