// One line of a text trace (.jsonl) parsed into a TraceRay: the type and
// range of each field, nothing that depends on other rays or on the scene
// (check_trace_ray and the reader's validator apply those rules). A pure
// function of the line, so that lines can be parsed on several threads.
#pragma once
#include <string_view>

#include "trace/trace_record.h"

namespace vbsim {

/// Parses the JSON object `line` into `out`. Throws TraceFieldProblem naming
/// the field at fault (its line is the caller's to add).
void parse_trace_ray_line(std::string_view line, TraceRay& out);

}  // namespace vbsim
