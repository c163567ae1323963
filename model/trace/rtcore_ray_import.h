// Ray files of rtcore-systemc, the other open SystemC ray-tracing core model:
// headerless little-endian records of seven float32 (ox oy oz dx dy dz tmax),
// tmin 0, traced against a PLY mesh named separately. The reader presents such
// a file as a vbsim trace; the writer exports o, d and tmax of vbsim rays.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "trace/record_file_reader.h"
#include "trace/record_file_writer.h"
#include "trace/trace_source.h"
#include "trace/trace_validation.h"

namespace vbsim {

constexpr std::size_t kRtcoreRayRecordBytes = 7 * 4;

class RtcoreRayReader final : public TraceSource {
 public:
  /// Opens the ray file `path`; `scene_path` (usable from the working
  /// directory) becomes the header's scene_path, and `scene` is that path
  /// relative to the ray file's directory. A file size that is not a multiple
  /// of 28 bytes is an error naming the partial last record. Throws TraceError.
  RtcoreRayReader(std::string path, std::string scene_path);

  const TraceHeader& header() const override { return header_; }
  /// Next ray: id = record index, kind primary, tmin 0, no parent data.
  /// Rejects a non-finite origin, a zero or non-finite direction, and a
  /// negative or NaN tmax, naming "record N" and the field.
  bool next(TraceRay& out) override;
  /// Kept for the interface: rtcore rays name no triangles.
  void set_triangle_count(int32_t n) override { triangle_count_ = n; }
  const std::string& path() const override { return path_; }
  TraceError error_at_last_ray(const std::string& field,
                               const std::string& message) const override;

  /// Number of records in the file (from its size), or -1 when not known.
  int64_t record_count() const { return records_.record_count(); }

 private:
  std::string path_;
  TraceHeader header_;
  int32_t triangle_count_ = -1;
  RecordFileReader records_;
};

/// Writes rays in the rtcore-systemc format. Lossy by nature: it keeps o, d
/// and tmax only (ids become record indices; kind, parent data and expect are
/// dropped); a ray with tmin other than +0 is an error, the format has no tmin.
class RtcoreRayWriter final : public TraceSink {
 public:
  /// Creates (or truncates) `path`. Throws TraceError.
  explicit RtcoreRayWriter(std::string path);

  /// Appends o, d and tmax; errors name the record index and field.
  void write(const TraceRay& ray) override;
  void close() override { records_.close(); }
  const std::string& path() const override { return path_; }

 private:
  std::string path_;
  RecordFileWriter records_;
};

}  // namespace vbsim
