#include "trace/record_file_writer.h"

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "trace/trace_error.h"

namespace vbsim {

RecordFileWriter::RecordFileWriter(std::string path, std::size_t record_bytes,
                                   std::size_t records_per_write, std::string_view prefix)
    : path_(std::move(path)), record_bytes_(record_bytes) {
  try {
    out_ = std::make_unique<AtomicOutputFile>(path_, true);
  } catch (const OutputError& e) {
    throw TraceError::in_file(path_, e.message);
  }
  out_->stream().write(prefix.data(), static_cast<std::streamsize>(prefix.size()));
  if (!out_->stream()) throw TraceError::in_file(path_, fmt::format("write failed: {}", std::strerror(errno)));
  buffer_.resize(records_per_write * record_bytes_);
}

void RecordFileWriter::require_open() const {
  if (closed_) throw TraceError::in_file(path_, "write after close");
}

void RecordFileWriter::flush_buffer() {
  std::ostream& out = out_->stream();
  out.write(reinterpret_cast<const char*>(buffer_.data()), static_cast<std::streamsize>(used_));
  used_ = 0;
  if (!out) throw TraceError::in_file(path_, fmt::format("write failed: {}", std::strerror(errno)));
}

void RecordFileWriter::close() {
  if (closed_) return;
  closed_ = true;
  flush_buffer();
  try {
    out_->commit();
  } catch (const OutputError& e) {
    throw TraceError::in_file(path_, e.message);
  }
}

}  // namespace vbsim
