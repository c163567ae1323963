// TextTraceWriter: writes a text trace (.jsonl): the header line, then one
// compact JSON object per ray. Fields equal to their defaults are omitted;
// numbers are the shortest decimals that read back to the same float32
// (expect.t: the same double), so reading the output gives identical rays.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "io/atomic_output_file.h"
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
  /// Creates `path` (under a temporary name until close(): AtomicOutputFile)
  /// and writes the header line. Throws TraceError.
  TextTraceWriter(std::string path, const TraceHeader& header);

  /// Validates `ray` as a reader would (ids unique, values finite, ...) and
  /// appends its line; throws TraceError naming the output line and field.
  void write(const TraceRay& ray) override;
  /// Writes the file out and gives it its name; throws TraceError on a write error.
  /// A writer destroyed without close() leaves no file.
  void close() override;
  const std::string& path() const override { return path_; }

 private:
  void flush_line();

  std::string path_;
  bool masks_declared_;  ///< the header has triangle_masks: rays may carry a mask
  std::unique_ptr<AtomicOutputFile> out_;
  fmt::memory_buffer line_;
  int64_t line_number_ = 0;  ///< 1-based number of the line last written
  TraceRayValidator validator_;
  bool closed_ = false;
};

}  // namespace vbsim
