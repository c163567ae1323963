// TextLineBlock: lines of a text trace read ahead of the reader and parsed
// into rays on several threads (parse_trace_ray_line, a pure function of the
// line). The reader hands them out one by one, in file order, and applies the
// rules that relate a ray to the rays before it as it goes, so what it returns
// and the errors it throws do not depend on the thread count. Memory: one
// block of lines; the lines' strings keep their capacity from block to block.
#pragma once
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "trace/trace_record.h"

namespace vbsim {

class TextLineBlock {
 public:
  /// The string the next line is to be read into.
  std::string& free_line();
  /// Keeps the line just read into free_line(), found at `line_number`.
  void commit(int64_t line_number);
  /// Parses every line kept, on up to `threads` threads.
  void parse(int threads);
  /// Forgets every line (their strings' memory is kept for the next block).
  void clear() { count_ = 0; }

  std::size_t size() const { return count_; }
  int64_t line_number(std::size_t i) const { return numbers_[i]; }
  /// Line i's ray into `out`, or rethrows what parsing it threw
  /// (TraceFieldProblem for a field at fault).
  void take(std::size_t i, TraceRay& out) const;

 private:
  std::vector<std::string> lines_;
  std::vector<int64_t> numbers_;
  std::vector<TraceRay> rays_;
  std::vector<std::exception_ptr> errors_;
  std::size_t count_ = 0;
};

}  // namespace vbsim
