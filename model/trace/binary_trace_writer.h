// BinaryTraceWriter: writes a binary trace (.vbt, layout in
// binary_trace_format.h): preamble and header JSON, then one 96-byte record
// per ray, buffered. Validates each ray as the readers do.
#pragma once
#include <cstdint>
#include <string>

#include "trace/record_file_writer.h"
#include "trace/trace_source.h"
#include "trace/trace_validation.h"

namespace vbsim {

class BinaryTraceWriter final : public TraceSink {
 public:
  /// Creates (or truncates) `path` and writes preamble and header. Throws TraceError.
  BinaryTraceWriter(std::string path, const TraceHeader& header);

  /// Validates and appends one record; errors name the record index and field.
  void write(const TraceRay& ray) override;
  void close() override { records_.close(); }
  const std::string& path() const override { return path_; }

  int64_t records_written() const { return records_.records_written(); }

 private:
  std::string path_;
  uint32_t version_;  ///< binary_trace_layout_for(header)
  RecordFileWriter records_;
  TraceRayValidator validator_;
};

}  // namespace vbsim
