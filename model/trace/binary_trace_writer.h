// BinaryTraceWriter: writes a binary trace (.vbt, layout in
// binary_trace_format.h): preamble and header JSON, then one 96-byte record
// per ray, buffered. Validates each ray as the readers do.
#pragma once
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "trace/trace_source.h"
#include "trace/trace_validation.h"

namespace vbsim {

class BinaryTraceWriter final : public TraceSink {
 public:
  /// Creates (or truncates) `path` and writes preamble and header. Throws TraceError.
  BinaryTraceWriter(std::string path, const TraceHeader& header);
  ~BinaryTraceWriter() override;

  /// Validates and appends one record; errors name the record index and field.
  void write(const TraceRay& ray) override;
  void close() override;
  const std::string& path() const override { return path_; }

  int64_t records_written() const { return records_; }

 private:
  void flush_buffer();

  std::string path_;
  std::ofstream out_;
  std::vector<uint8_t> buffer_;
  std::size_t used_ = 0;
  int64_t records_ = 0;
  TraceRayValidator validator_;
  bool closed_ = false;
};

}  // namespace vbsim
