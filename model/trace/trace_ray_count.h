// How many rays a trace file holds, without parsing it: for progress displays.
// A binary trace knows it from its size; a text trace is scanned for its ray
// lines (every line but the header, blank lines and `#` comments), about a
// second per GB. Not a validation: the readers check the records.
#pragma once
#include <cstdint>
#include <string>

namespace vbsim {

/// The ray count, or 0 when the file cannot be read or is not a regular file
/// (a pipe is never opened twice).
uint64_t count_trace_rays(const std::string& path);

}  // namespace vbsim
