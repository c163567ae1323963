// RecordFileReader: streams the fixed-size records that fill a file from a
// byte offset to its end, through one buffer allocated when it opens, so that
// reading a record never allocates. The binary trace and rtcore ray readers
// decode its records; it owns the buffering, the record count and the errors
// for a partial last record, a short read and a read error.
#pragma once
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace vbsim {

/// How a file's records look, for reading and for error messages.
struct RecordFileShape {
  std::size_t record_bytes = 0;      ///< bytes of one record, > 0
  std::size_t records_per_read = 0;  ///< records one read of the file fetches, > 0
  /// Named in parentheses after "N-byte record" in truncation errors (e.g.
  /// "7 float32: ox oy oz dx dy dz tmax"); empty for none.
  std::string layout;
};

class RecordFileReader {
 public:
  /// Opens `path` for binary reading; throws TraceError "cannot open: <reason>".
  static std::ifstream open_file(const std::string& path);

  /// A reader of no file; next() returns nullptr. Move-assign a real one over it.
  RecordFileReader() = default;
  /// Takes over `in`, opened on `path` and positioned at byte `records_start`
  /// (the caller has read what precedes the records). When the file's size is
  /// known, counts its records and throws TraceError at the partial last
  /// record's index if the size leaves one.
  RecordFileReader(std::string path, std::ifstream in, uint64_t records_start,
                   RecordFileShape shape);

  /// The next record's shape.record_bytes bytes, valid until the next call;
  /// nullptr at the end. Throws TraceError at the index of the record being
  /// read for a partial last record (a short read) or a read error.
  const uint8_t* next();

  /// Records next() has returned so far; the last one's 0-based index is one less.
  int64_t records_read() const { return records_read_; }
  /// Number of records from the file's size, or -1 when the size is not known
  /// (a pipe, say); then only reading finds a partial last record.
  int64_t record_count() const { return record_count_; }

 private:
  /// Refills the buffer; false when no complete record is left.
  bool fill();
  /// "truncated: the file ends <bytes> bytes into this <N>-byte record (<layout>)".
  std::string truncated_record_message(std::size_t bytes) const;

  std::string path_;
  std::ifstream in_;
  RecordFileShape shape_;
  std::vector<uint8_t> buffer_;
  std::size_t pos_ = 0;             ///< next unread byte in buffer_
  std::size_t end_ = 0;             ///< end of the complete records in buffer_
  std::size_t trailing_bytes_ = 0;  ///< bytes of a partial record after end_
  int64_t records_read_ = 0;
  int64_t record_count_ = -1;
};

}  // namespace vbsim
