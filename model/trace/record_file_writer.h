// RecordFileWriter: writes a file of fixed-size records after an optional
// prefix (a format's preamble and header), through one buffer allocated when
// it opens, so that appending a record never allocates. The binary trace and
// rtcore ray writers encode the records; it owns the buffering, the record
// count, closing and the I/O errors.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "io/atomic_output_file.h"

namespace vbsim {

class RecordFileWriter {
 public:
  /// Creates `path` (under a temporary name until close(): AtomicOutputFile)
  /// and writes `prefix`, the bytes before the first record. Records are `record_bytes` long, written out
  /// `records_per_write` at a time. Throws TraceError "cannot create: <reason>"
  /// or "write failed".
  RecordFileWriter(std::string path, std::size_t record_bytes, std::size_t records_per_write,
                   std::string_view prefix = {});
  /// Without close(), removes the temporary: no file appears.
  ~RecordFileWriter() = default;
  RecordFileWriter(const RecordFileWriter&) = delete;
  RecordFileWriter& operator=(const RecordFileWriter&) = delete;

  /// Throws TraceError "write after close" once close() was called.
  void require_open() const;
  /// Appends one record: `encode(uint8_t* record)` fills its record_bytes
  /// bytes. Writes the buffer out when it is full; throws TraceError "write
  /// failed" then.
  template <class Encode>
  void append(Encode&& encode) {
    encode(buffer_.data() + used_);
    used_ += record_bytes_;
    ++records_written_;
    if (used_ == buffer_.size()) flush_buffer();
  }
  /// Writes out the buffered records, closes the file and gives it its name;
  /// a second call does nothing. Throws TraceError "write failed: REASON".
  void close();

  /// Records appended so far, which is the 0-based index of the next one.
  int64_t records_written() const { return records_written_; }

 private:
  void flush_buffer();

  std::string path_;
  std::unique_ptr<AtomicOutputFile> out_;
  std::size_t record_bytes_;
  std::vector<uint8_t> buffer_;
  std::size_t used_ = 0;  ///< bytes of buffered records in buffer_
  int64_t records_written_ = 0;
  bool closed_ = false;
};

}  // namespace vbsim
