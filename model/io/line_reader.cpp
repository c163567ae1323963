#include "io/line_reader.h"

namespace vbsim {

LineRead read_bounded_line(std::istream& in, std::string& line, std::size_t limit) {
  line.clear();
  bool extracted = false;
  char block[1 << 16];
  for (;;) {
    in.getline(block, sizeof block);
    const std::streamsize got = in.gcount();
    extracted = extracted || got > 0;
    const bool full = in.fail() && !in.eof() && !in.bad() && got == static_cast<std::streamsize>(sizeof block - 1);
    // A full block: the line goes on (getline stored sizeof block - 1 bytes
    // and found no '\n'); otherwise the '\n', if any, was counted in got.
    const std::size_t stored = full || in.eof() ? static_cast<std::size_t>(got) : static_cast<std::size_t>(got) - 1;
    if (got > 0) line.append(block, stored);
    if (full) in.clear(in.rdstate() & ~std::ios::failbit);
    if (line.size() > limit) return LineRead::kTooLong;
    if (full) continue;
    if (in.bad()) return LineRead::kEnd;
    if (in.eof()) {
      // The last line without its '\n' is a line; nothing at all is the end.
      if (!extracted) return LineRead::kEnd;
      in.clear(in.rdstate() & ~std::ios::failbit);
      return LineRead::kLine;
    }
    return LineRead::kLine;
  }
}

}  // namespace vbsim
