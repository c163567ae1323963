#include "trace/binary_trace_reader.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "trace/binary_trace_format.h"
#include "trace/trace_header_json.h"
#include "trace/trace_json_values.h"

namespace vbsim {

namespace {

constexpr std::size_t kRecordsPerRead = 1024;

std::string truncated_record_message(std::size_t bytes) {
  return fmt::format("truncated: the file ends {} bytes into this {}-byte record", bytes,
                     kBinaryTraceRecordBytes);
}

}  // namespace

BinaryTraceReader::BinaryTraceReader(std::string path) : path_(std::move(path)) {
  in_.open(path_, std::ios::in | std::ios::binary);
  if (!in_) throw TraceError::in_file(path_, fmt::format("cannot open: {}", std::strerror(errno)));

  uint8_t preamble[kBinaryTracePreambleBytes];
  in_.read(reinterpret_cast<char*>(preamble), sizeof preamble);
  std::size_t got = static_cast<std::size_t>(in_.gcount());
  if (got < sizeof kBinaryTraceMagic ||
      std::memcmp(preamble, kBinaryTraceMagic, sizeof kBinaryTraceMagic) != 0)
    throw TraceError::in_file(path_, "not a binary vbsim trace (no \"VBSIMTRB\" magic)");
  if (got < sizeof preamble)
    throw TraceError::in_file(path_, "truncated: the file ends inside its 16-byte preamble");
  uint32_t version = load_le_u32(preamble + 8);
  if (version != kBinaryTraceLayoutVersion)
    throw TraceError::in_file(path_, fmt::format("unsupported binary layout version {} (this "
                                                 "reader reads {})",
                                                 version, kBinaryTraceLayoutVersion));
  uint32_t header_bytes = load_le_u32(preamble + 12);
  if (header_bytes == 0 || header_bytes > kBinaryTraceMaxHeaderBytes)
    throw TraceError::in_header(path_, "", fmt::format("implausible header length {}", header_bytes));

  std::size_t padded = binary_trace_padded_header_bytes(header_bytes);
  std::string header_text(padded, ' ');
  in_.read(header_text.data(), static_cast<std::streamsize>(padded));
  if (static_cast<std::size_t>(in_.gcount()) != padded)
    throw TraceError::in_header(path_, "", fmt::format("truncated: the file ends inside the "
                                                       "{}-byte header",
                                                       padded));
  header_text.resize(header_bytes);
  try {
    header_ = parse_trace_header(parse_json_object_line(header_text), path_);
  } catch (const TraceFieldProblem& p) {
    throw TraceError::in_header(path_, p.field, p.message);
  }

  // A regular file's size tells at once whether the last record is complete;
  // fill() still catches a short read for files whose size is not known.
  std::error_code ec;
  uintmax_t size = std::filesystem::file_size(path_, ec);
  if (!ec) {
    uintmax_t payload = size - kBinaryTracePreambleBytes - padded;
    record_count_ = static_cast<int64_t>(payload / kBinaryTraceRecordBytes);
    if (payload % kBinaryTraceRecordBytes != 0)
      throw TraceError::at_record(path_, record_count_, "",
                                  truncated_record_message(payload % kBinaryTraceRecordBytes));
  }
  buffer_.resize(kRecordsPerRead * kBinaryTraceRecordBytes);
}

bool BinaryTraceReader::fill() {
  // Keep a partial record's bytes at the front: a short read need not be the end.
  std::size_t kept = trailing_bytes_;
  std::memmove(buffer_.data(), buffer_.data() + end_, kept);
  in_.read(reinterpret_cast<char*>(buffer_.data() + kept),
           static_cast<std::streamsize>(buffer_.size() - kept));
  std::size_t have = kept + static_cast<std::size_t>(in_.gcount());
  if (in_.bad()) throw TraceError::at_record(path_, next_record_, "", "read error");
  pos_ = 0;
  end_ = have / kBinaryTraceRecordBytes * kBinaryTraceRecordBytes;
  trailing_bytes_ = have - end_;
  if (end_ > 0) return true;
  if (trailing_bytes_ > 0)
    throw TraceError::at_record(path_, next_record_, "", truncated_record_message(trailing_bytes_));
  return false;
}

bool BinaryTraceReader::next(TraceRay& out) {
  if (pos_ == end_ && !fill()) return false;
  const uint8_t* record = buffer_.data() + pos_;
  pos_ += kBinaryTraceRecordBytes;
  int64_t index = next_record_++;
  TraceFieldProblem problem;
  if (!decode_binary_trace_record(record, out, problem) || !validator_.check(out, problem))
    throw TraceError::at_record(path_, index, problem.field, problem.message);
  return true;
}

TraceError BinaryTraceReader::error_at_last_ray(const std::string& field,
                                                const std::string& message) const {
  return TraceError::at_record(path_, next_record_ - 1, field, message);
}

}  // namespace vbsim
