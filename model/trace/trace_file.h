// Opening and creating trace files by kind: text (.jsonl) or binary (.vbt),
// and copying a trace from any source to any sink.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "trace/trace_source.h"

namespace vbsim {

/// File extension that selects the binary form when writing.
constexpr const char* kBinaryTraceExtension = ".vbt";

/// True when `path` ends in ".vbt".
bool is_binary_trace_path(const std::string& path);

/// Opens a trace for streaming: binary when the file starts with the
/// "VBSIMTRB" magic (its first byte decides; the binary reader checks the
/// rest), text otherwise (whatever its extension). Opens `path` once, so it
/// may be a pipe. Reads and validates the header; throws TraceError.
std::unique_ptr<TraceSource> open_trace(const std::string& path);

/// Creates a trace file and writes `header`: binary when `path` ends in
/// ".vbt", text (.jsonl) otherwise. Throws TraceError.
std::unique_ptr<TraceSink> create_trace_writer(const std::string& path, const TraceHeader& header);

/// Writes every remaining ray of `in` to `out`, in order; returns how many.
/// Does not close `out`. Throws TraceError from either side.
int64_t copy_trace(TraceSource& in, TraceSink& out);

/// Converts the trace `in_path` (text or binary) to `out_path` (form chosen as
/// create_trace_writer does), rewriting the header's scene relative to the
/// output's directory; closes the output and returns the number of rays.
int64_t convert_trace_file(const std::string& in_path, const std::string& out_path);

}  // namespace vbsim
