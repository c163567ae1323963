// TextTraceWriter: writes a text trace (.jsonl): the header line, then one
// compact JSON object per ray. Fields equal to their defaults are omitted;
// numbers are the shortest decimals that read back to the same float32
// (expect.t: the same double), so reading the output gives identical rays.
#pragma once
#include <cstdint>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "trace/trace_source.h"
#include "trace/trace_validation.h"

namespace vbsim {

/// Appends one ray as the JSON object of a text trace line (no newline), in
/// the field order id, parent, kind, o, d, tmin, tmax, parent_prim, parent_t,
/// parent_uv, parent_ns, sign, expect. Omitted: parent -1, kind primary,
/// tmin +0, tmax +inf, parent_prim -1, sign -1 and absent optional fields.
/// Precondition: check_trace_ray(ray, -1, ...) passes (all values finite).
void append_trace_ray_json(fmt::memory_buffer& out, const TraceRay& ray);

class TextTraceWriter final : public TraceSink {
 public:
  /// Creates (or truncates) `path` and writes the header line. Throws TraceError.
  TextTraceWriter(std::string path, const TraceHeader& header);
  ~TextTraceWriter() override;

  /// Validates `ray` as a reader would (ids unique, values finite, ...) and
  /// appends its line; throws TraceError naming the output line and field.
  void write(const TraceRay& ray) override;
  void close() override;
  const std::string& path() const override { return path_; }

 private:
  void flush_line();

  std::string path_;
  std::ofstream out_;
  fmt::memory_buffer line_;
  int64_t line_number_ = 0;  ///< 1-based number of the line last written
  TraceRayValidator validator_;
  bool closed_ = false;
};

}  // namespace vbsim
