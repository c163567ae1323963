// BinaryTraceReader: streams a binary trace (.vbt, layout in
// binary_trace_format.h) record by record through a fixed-size buffer,
// validating every ray with the same rules as the text reader.
#pragma once
#include <cstdint>
#include <fstream>
#include <string>

#include "trace/record_file_reader.h"
#include "trace/trace_source.h"
#include "trace/trace_validation.h"

namespace vbsim {

class BinaryTraceReader final : public TraceSource {
 public:
  /// Opens `path`, checks magic and layout version, reads and validates the
  /// header JSON, and rejects a file whose size leaves a partial last record
  /// (error at that record's index). Throws TraceError.
  explicit BinaryTraceReader(std::string path);
  /// The same on `in`, already opened on `path` and not read from.
  BinaryTraceReader(std::string path, std::ifstream in);

  const TraceHeader& header() const override { return header_; }
  /// Next record; false at the end. Errors name "record N" (0-based) and the field.
  bool next(TraceRay& out) override;
  void set_triangle_count(int32_t n) override { validator_.set_triangle_count(n); }
  int64_t ids_not_checked() const override { return validator_.ids_not_checked(); }
  const std::string& path() const override { return path_; }
  TraceError error_at_last_ray(const std::string& field,
                               const std::string& message) const override;

  /// Number of records in the file (from its size), or -1 when not known.
  int64_t record_count() const { return records_.record_count(); }

 private:
  std::string path_;
  TraceHeader header_;
  TraceRayValidator validator_;
  uint32_t version_ = 1;      ///< layout 1, or 2 (with the reference answers)
  RecordFileReader records_;  ///< the 96-byte (layout 2: 104-byte) records after the header
};

}  // namespace vbsim
