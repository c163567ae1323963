#include "trace/binary_trace_writer.h"

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "trace/binary_trace_format.h"
#include "trace/trace_header_json.h"

namespace vbsim {

namespace {
constexpr std::size_t kRecordsPerWrite = 1024;
}

BinaryTraceWriter::BinaryTraceWriter(std::string path, const TraceHeader& header)
    : path_(std::move(path)) {
  std::string header_text;
  try {
    header_text = trace_header_json(header);
  } catch (const TraceFieldProblem& p) {
    throw TraceError::in_header(path_, p.field, p.message);
  }
  if (header_text.size() > kBinaryTraceMaxHeaderBytes)
    throw TraceError::in_header(path_, "", "header JSON is longer than 16 MiB");
  out_.open(path_, std::ios::out | std::ios::binary | std::ios::trunc);
  if (!out_)
    throw TraceError::in_file(path_, fmt::format("cannot create: {}", std::strerror(errno)));
  uint8_t preamble[kBinaryTracePreambleBytes];
  encode_binary_trace_preamble(static_cast<uint32_t>(header_text.size()), preamble);
  header_text.resize(binary_trace_padded_header_bytes(header_text.size()), ' ');
  out_.write(reinterpret_cast<const char*>(preamble), sizeof preamble);
  out_.write(header_text.data(), static_cast<std::streamsize>(header_text.size()));
  if (!out_) throw TraceError::in_file(path_, "write failed");
  buffer_.resize(kRecordsPerWrite * kBinaryTraceRecordBytes);
}

BinaryTraceWriter::~BinaryTraceWriter() {
  if (!closed_) {
    try {
      close();
    } catch (const TraceError&) {
      // Destructors must not throw; close() reports errors to callers who ask.
    }
  }
}

void BinaryTraceWriter::write(const TraceRay& ray) {
  if (closed_) throw TraceError::in_file(path_, "write after close");
  TraceFieldProblem problem;
  if (!validator_.check(ray, problem))
    throw TraceError::at_record(path_, records_, problem.field, problem.message);
  encode_binary_trace_record(ray, buffer_.data() + used_);
  used_ += kBinaryTraceRecordBytes;
  ++records_;
  if (used_ == buffer_.size()) flush_buffer();
}

void BinaryTraceWriter::flush_buffer() {
  out_.write(reinterpret_cast<const char*>(buffer_.data()), static_cast<std::streamsize>(used_));
  used_ = 0;
  if (!out_) throw TraceError::in_file(path_, "write failed");
}

void BinaryTraceWriter::close() {
  if (closed_) return;
  closed_ = true;
  flush_buffer();
  out_.close();
  if (!out_) throw TraceError::in_file(path_, "write failed while closing");
}

}  // namespace vbsim
