// Lines of a text input read with a bound: an endless line (/dev/zero, a
// binary file given as text) is refused once it passes the limit, before
// memory grows with it.
#pragma once
#include <cstddef>
#include <istream>
#include <string>

namespace vbsim {

/// Longest line of a text input vbsim reads line by line (a trace line, a
/// header with its provenance, a hits line): 16 MiB, as a binary trace's
/// header. A ray's line is about 200 bytes.
constexpr std::size_t kMaxTextLineBytes = std::size_t{16} << 20;

enum class LineRead {
  kLine,     ///< a line (its '\n' dropped; the last line may lack it)
  kEnd,      ///< nothing more (or a read error: check in.bad())
  kTooLong,  ///< more than `limit` bytes without a '\n': reading stopped there
};

/// Reads the next line of `in` into `line`, as std::getline does, but keeps
/// at most `limit` bytes of it.
LineRead read_bounded_line(std::istream& in, std::string& line, std::size_t limit = kMaxTextLineBytes);

}  // namespace vbsim
