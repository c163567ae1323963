// TextTraceReader: streams a text trace (.jsonl), one JSON object per line,
// validating every ray as ../../docs/trace-binary.md summarises and the trace
// format spec defines. Holds one line at a time, plus the ids seen so far; with
// parse threads, a block of lines read ahead (text_line_block.h).
#pragma once
#include <cstdint>
#include <fstream>
#include <string>

#include "trace/text_line_block.h"
#include "trace/trace_source.h"
#include "trace/trace_validation.h"

namespace vbsim {

class TextTraceReader final : public TraceSource {
 public:
  /// Opens `path` and reads and validates its header line (blank lines and
  /// '#' comment lines before it are skipped). Throws TraceError.
  explicit TextTraceReader(std::string path);
  /// The same on `in`, already opened on `path` and not read from (so that a
  /// pipe is opened once).
  TextTraceReader(std::string path, std::ifstream in);

  const TraceHeader& header() const override { return header_; }
  /// Next ray in file order; false at the end. Throws TraceError naming the
  /// line and field of the first rule a line breaks.
  bool next(TraceRay& out) override;
  void set_triangle_count(int32_t n) override { validator_.set_triangle_count(n); }
  /// With more than one thread, lines are read ahead in blocks and parsed on
  /// that many threads; next() returns the same rays and throws the same
  /// errors, in the same order, as with one.
  void set_parse_threads(int threads) override { parse_threads_ = threads; }
  int64_t ids_not_checked() const override { return validator_.ids_not_checked(); }
  const std::string& path() const override { return path_; }
  TraceError error_at_last_ray(const std::string& field,
                               const std::string& message) const override;

  /// 1-based line number of the line last read (the ray last returned).
  int64_t line_number() const { return line_number_; }

 private:
  /// Reads up to the next line that is neither blank nor a comment into
  /// `line`; false at end of file. A line longer than kMaxTextLineBytes
  /// (io/line_reader.h) is an error at its line, and the reader reads nothing
  /// more after it.
  bool read_content_line(std::string& line);
  /// The rules that relate `out`, parsed from line line_number_, to the rays
  /// before it and to the header; throws TraceError at that line.
  void validate(const TraceRay& out);
  /// Reads the next block of lines ahead and parses them (parse threads > 1);
  /// an error reading a line ends the block and is kept in ahead_error_.
  void read_ahead();
  bool next_ahead(TraceRay& out);

  std::string path_;
  std::ifstream in_;
  std::string line_;
  int64_t read_line_ = 0;    ///< lines read from the file so far
  int64_t line_number_ = 0;  ///< the line of the ray last returned
  int parse_threads_ = 1;
  TextLineBlock ahead_;
  std::size_t ahead_next_ = 0;     ///< the line of ahead_ next() returns next
  std::exception_ptr ahead_error_;  ///< an error reading the line after ahead_'s last
  int64_t ahead_error_line_ = 0;
  bool stopped_ = false;  ///< a line passed kMaxTextLineBytes: the rest is not read
  TraceHeader header_;
  TraceRayValidator validator_;
};

}  // namespace vbsim
