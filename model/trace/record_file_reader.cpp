#include "trace/record_file_reader.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "trace/trace_error.h"

namespace vbsim {

std::ifstream RecordFileReader::open_file(const std::string& path) {
  std::ifstream in(path, std::ios::in | std::ios::binary);
  if (!in) throw TraceError::in_file(path, fmt::format("cannot open: {}", std::strerror(errno)));
  return in;
}

RecordFileReader::RecordFileReader(std::string path, std::ifstream in, uint64_t records_start,
                                   RecordFileShape shape)
    : path_(std::move(path)), in_(std::move(in)), shape_(std::move(shape)) {
  // A regular file's size tells at once whether the last record is complete;
  // fill() still catches a short read for files whose size is not known.
  std::error_code ec;
  uintmax_t size = std::filesystem::file_size(path_, ec);
  if (!ec && size >= records_start) {
    uintmax_t payload = size - records_start;
    record_count_ = static_cast<int64_t>(payload / shape_.record_bytes);
    if (payload % shape_.record_bytes != 0)
      throw TraceError::at_record(path_, record_count_, "",
                                  truncated_record_message(payload % shape_.record_bytes));
  }
  buffer_.resize(shape_.records_per_read * shape_.record_bytes);
}

const uint8_t* RecordFileReader::next() {
  if (pos_ == end_ && !fill()) return nullptr;
  const uint8_t* record = buffer_.data() + pos_;
  pos_ += shape_.record_bytes;
  ++records_read_;
  return record;
}

bool RecordFileReader::fill() {
  if (buffer_.empty()) return false;  // default-constructed: no file
  // Keep a partial record's bytes at the front: a short read need not be the end.
  std::size_t kept = trailing_bytes_;
  std::memmove(buffer_.data(), buffer_.data() + end_, kept);
  in_.read(reinterpret_cast<char*>(buffer_.data() + kept),
           static_cast<std::streamsize>(buffer_.size() - kept));
  std::size_t have = kept + static_cast<std::size_t>(in_.gcount());
  if (in_.bad()) throw TraceError::at_record(path_, records_read_, "", "read error");
  pos_ = 0;
  end_ = have / shape_.record_bytes * shape_.record_bytes;
  trailing_bytes_ = have - end_;
  if (end_ > 0) return true;
  if (trailing_bytes_ > 0)
    throw TraceError::at_record(path_, records_read_, "", truncated_record_message(trailing_bytes_));
  return false;
}

std::string RecordFileReader::truncated_record_message(std::size_t bytes) const {
  std::string message = fmt::format("truncated: the file ends {} bytes into this {}-byte record",
                                    bytes, shape_.record_bytes);
  if (!shape_.layout.empty()) message += fmt::format(" ({})", shape_.layout);
  return message;
}

}  // namespace vbsim
