// io/line_reader.h: lines read as std::getline reads them, but never more
// than the limit of one line.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

#include "io/line_reader.h"

using namespace vbsim;

namespace {

/// Every line of `text` as read_bounded_line returns it, "<too long>" for one
/// refused (which ends the reading).
std::vector<std::string> lines(const std::string& text, std::size_t limit) {
  std::istringstream in(text);
  std::vector<std::string> out;
  std::string line;
  for (LineRead r; (r = read_bounded_line(in, line, limit)) != LineRead::kEnd;) {
    if (r == LineRead::kTooLong) {
      out.push_back("<too long>");
      break;
    }
    out.push_back(line);
  }
  return out;
}

std::vector<std::string> getline_lines(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

TEST_CASE("line reader: lines as std::getline reads them, within the limit", "[io]") {
  const std::string longer(200000, 'x');  // several of the reader's blocks
  for (const std::string& text :
       {std::string(""), std::string("\n"), std::string("a"), std::string("a\n"), std::string("a\n\nb"),
        std::string("a\r\nb\n\n"), std::string("nul\0inside\n", 11), longer, longer + "\n" + longer + "\nz",
        std::string(65535, 'y') + "\n" + std::string(65536, 'y') + "\n" + std::string(65537, 'y')}) {
    INFO(text.size());
    CHECK(lines(text, kMaxTextLineBytes) == getline_lines(text));
  }
}

TEST_CASE("line reader: a line longer than the limit is refused where it passes it", "[io]") {
  CHECK(lines("abc\nabcd\n", 4) == std::vector<std::string>{"abc", "abcd"});
  CHECK(lines("abc\nabcde\nx\n", 4) == std::vector<std::string>{"abc", "<too long>"});
  CHECK(lines(std::string(300000, 'x'), 100000) == std::vector<std::string>{"<too long>"});
  CHECK(lines(std::string(300000, 'x'), 300000) == std::vector<std::string>{std::string(300000, 'x')});
  // Reading stops at the limit: the rest of an endless line is never read.
  std::istringstream in(std::string(1 << 20, '\0'));
  std::string line;
  CHECK(read_bounded_line(in, line, 1000) == LineRead::kTooLong);
  CHECK(line.size() <= (1u << 16) + 1000);
  CHECK(in.tellg() <= (1 << 16) + 1000);
}
