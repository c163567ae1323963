// The trace header object, shared by the text form (its first line) and the
// binary form (its embedded header JSON): parsing with validation, writing,
// and the rule that `scene` is a path relative to the trace file.
#pragma once
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "trace/trace_record.h"

namespace vbsim {

constexpr const char* kTraceFormatName = "vbsim-trace";  ///< the header's "format" value
constexpr int kTraceFormatVersion = 1;                     ///< the header's "version" value

/// Reads a header object: format "vbsim-trace", version 1, scene (non-empty
/// string) required; light [3 numbers], generator, description (strings) and
/// transform [16 numbers], triangle_masks ([[first, count, mask], ...],
/// ascending, disjoint) and provenance (an object, kept as compact JSON)
/// optional; unknown fields ignored. scene_path is
/// `scene` resolved against the directory of `trace_path`.
/// Throws TraceFieldProblem naming the field.
TraceHeader parse_trace_header(const nlohmann::json& object, const std::string& trace_path);

/// The header as one compact JSON object (no newline), fields in the order
/// format, version, scene, light, generator, description, reference,
/// transform, triangle_masks, provenance (written as given); absent
/// optional fields and empty strings are omitted; numbers as shortest float32.
/// Throws TraceFieldProblem when a string is not UTF-8 or a number not finite.
std::string trace_header_json(const TraceHeader& header);

/// A ray's `mask` field: an integer 0 .. 2^32 - 1 (TraceFieldProblem "mask" otherwise).
uint32_t parse_ray_mask(const nlohmann::json& v);

/// `scene` (as written in a header) as a path usable from the working
/// directory: joined to the directory of `trace_path` unless absolute.
std::string resolve_scene_path(const std::string& scene, const std::string& trace_path);

/// The inverse: `scene_path` (usable from the working directory) rewritten
/// relative to the directory of `trace_path`, for the header of a trace
/// written there (absolute when no relative path exists).
std::string scene_relative_to(const std::string& scene_path, const std::string& trace_path);

}  // namespace vbsim
