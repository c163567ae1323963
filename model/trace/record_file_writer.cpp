#include "trace/record_file_writer.h"

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "trace/trace_error.h"

namespace vbsim {

RecordFileWriter::RecordFileWriter(std::string path, std::size_t record_bytes,
                                   std::size_t records_per_write, std::string_view prefix)
    : path_(std::move(path)), record_bytes_(record_bytes) {
  out_.open(path_, std::ios::out | std::ios::binary | std::ios::trunc);
  if (!out_)
    throw TraceError::in_file(path_, fmt::format("cannot create: {}", std::strerror(errno)));
  out_.write(prefix.data(), static_cast<std::streamsize>(prefix.size()));
  if (!out_) throw TraceError::in_file(path_, "write failed");
  buffer_.resize(records_per_write * record_bytes_);
}

RecordFileWriter::~RecordFileWriter() {
  if (!closed_) {
    try {
      close();
    } catch (const TraceError&) {
      // Destructors must not throw; close() reports errors to callers who ask.
    }
  }
}

void RecordFileWriter::require_open() const {
  if (closed_) throw TraceError::in_file(path_, "write after close");
}

void RecordFileWriter::flush_buffer() {
  out_.write(reinterpret_cast<const char*>(buffer_.data()), static_cast<std::streamsize>(used_));
  used_ = 0;
  if (!out_) throw TraceError::in_file(path_, "write failed");
}

void RecordFileWriter::close() {
  if (closed_) return;
  closed_ = true;
  flush_buffer();
  out_.close();
  if (!out_) throw TraceError::in_file(path_, "write failed while closing");
}

}  // namespace vbsim
