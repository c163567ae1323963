#include "scene/obj_validator.h"

#include <fmt/format.h>

#include <cstdlib>
#include <vector>

#include "progress/work_progress.h"
#include "scene/scene.h"

namespace vbsim {

namespace {

constexpr size_t kMaxLineBytes = 1 << 16;
/// Bytes between two progress reports.
constexpr size_t kReportBytes = size_t{1} << 20;
/// Longest number of a plain file (ObjSummary::plain): far below the word
/// buffer assimp's OBJ parser copies a number into.
constexpr size_t kMaxPlainNumberChars = 64;

bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// [+-]digits[.digits][(e|E)[+-]digits], or +.digits / -.digits: what every
/// OBJ reader parses alike. A bare leading point (".5") is not: assimp 5.2.5
/// does not take it for a number and then fails on the line.
bool is_decimal(std::string_view s) {
  if (!s.empty() && s[0] == '.') return false;
  size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  size_t digits = 0;
  while (i < s.size() && is_digit(s[i])) ++i, ++digits;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && is_digit(s[i])) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    size_t exp_digits = 0;
    while (i < s.size() && is_digit(s[i])) ++i, ++exp_digits;
    if (exp_digits == 0 || exp_digits > 4) return false;
  }
  return i == s.size();
}

/// The words of `line` into `out` (cleared first; its room is kept from line to line).
void split(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
}

class ObjChecker {
 public:
  ObjChecker(const std::string& path) : path_(path) {}

  [[noreturn]] void fail(const std::string& why) const {
    throw SceneError(fmt::format("scene '{}': OBJ line {}: {}", path_, line_, why));
  }

  void line(std::string_view text, uint64_t number) {
    line_ = number;
    if (text.size() > kMaxLineBytes) fail("longer than 64 KiB");
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (text.find('\0') != std::string_view::npos) fail("a NUL byte: not a text file");
    if (!text.empty() && text.back() == '\\') fail("a line continued with '\\' is not supported");
    split(text, words_);
    const std::vector<std::string_view>& w = words_;
    if (w.empty() || w[0][0] == '#') return;
    const std::string_view key = w[0];
    const size_t args = w.size() - 1;
    const bool plain_statement = ((key == "v" || key == "f") && args == 3) || key == "vn" || key == "vt" || key == "s";
    if (text[0] == ' ' || text[0] == '\t' || !plain_statement) sum_.plain_statements = false;
    if (key == "v") {
      if (args != 3 && args != 4 && args != 6) fail("'v' takes 3 coordinates (and w, or r g b)");
      numbers(w);
      ++sum_.vertices;
    } else if (key == "vn") {
      if (args != 3) fail("'vn' takes 3 numbers");
      numbers(w);
      ++normals_;
    } else if (key == "vt") {
      if (args < 2 || args > 3) fail("'vt' takes 2 or 3 numbers");
      numbers(w);
      ++texcoords_;
    } else if (key == "f" || key == "l" || key == "p") {
      const size_t least = key == "f" ? 3 : key == "l" ? 2 : 1;
      if (args < least) fail(fmt::format("'{}' needs at least {} vertices", key, least));
      int form = -1;
      for (size_t k = 1; k < w.size(); ++k) reference(w[k], key == "f", form);
      if (key == "f") {
        ++sum_.faces;
        if (form >= 2) ++sum_.faces_with_normals;
        sum_.triangles += args - 2;
      }
    } else if (key == "g") {
      // A group may be unnamed: 3ds Max's exporter writes a bare `g` before
      // each object's vertices, and assimp reads it.
    } else if (key == "o" || key == "usemtl" || key == "mtllib") {
      if (args < 1) fail(fmt::format("'{}' needs a name", key));
    } else if (key == "s") {
      if (args != 1) fail("'s' takes one group: off, on or a number");
    } else {
      fail(fmt::format("unknown statement '{}'", key));
    }
  }

  const ObjSummary& summary() const { return sum_; }

 private:
  void numbers(const std::vector<std::string_view>& w) {
    for (size_t k = 1; k < w.size(); ++k) {
      if (w[k].size() > kMaxPlainNumberChars) sum_.plain_statements = false;
      if (!is_decimal(w[k]))
        fail(fmt::format("'{}' is not a decimal number{}", w[k],
                         w[k].substr(0, 1) == "." ? fmt::format(" assimp reads (write 0{})", w[k]) : ""));
    }
  }

  /// One index: a non-zero integer within the `count` elements defined so far.
  void index(std::string_view s, uint64_t count, const char* what) const {
    if (s.empty()) fail(fmt::format("an empty {} index", what));
    size_t i = s[0] == '-' ? 1 : 0;
    if (i == s.size() || s.size() - i > 18) fail(fmt::format("'{}' is not a {} index", s, what));
    for (size_t k = i; k < s.size(); ++k)
      if (!is_digit(s[k])) fail(fmt::format("'{}' is not a {} index", s, what));
    uint64_t magnitude = 0;  // at most 18 digits: no overflow
    for (size_t k = i; k < s.size(); ++k) magnitude = magnitude * 10 + static_cast<uint64_t>(s[k] - '0');
    const long long v = i == 1 ? -static_cast<long long>(magnitude) : static_cast<long long>(magnitude);
    if (v == 0) fail(fmt::format("{} index 0: OBJ indices start at 1", what));
    if (magnitude > count)
      fail(fmt::format("{} index {} names a {} not defined before this line ({} so far)", what, v, what, count));
  }

  /// A reference i, i/t, i//n or i/t/n; `form` is 0..3 for those, the same in one statement.
  void reference(std::string_view r, bool allow_normal, int& form) const {
    const size_t a = r.find('/');
    const size_t b = a == std::string_view::npos ? a : r.find('/', a + 1);
    if (b != std::string_view::npos && r.find('/', b + 1) != std::string_view::npos)
      fail(fmt::format("'{}' has more than two '/'", r));
    int this_form = 0;
    index(r.substr(0, a), sum_.vertices, "vertex");
    if (a != std::string_view::npos) {
      const std::string_view t = r.substr(a + 1, b == std::string_view::npos ? std::string_view::npos : b - a - 1);
      if (!t.empty()) index(t, texcoords_, "texture coordinate");
      this_form = t.empty() ? 0 : 1;
      if (b != std::string_view::npos) {
        if (!allow_normal) fail(fmt::format("'{}': lines and points have no normals", r));
        index(r.substr(b + 1), normals_, "normal");
        this_form = t.empty() ? 2 : 3;
      } else if (t.empty()) {
        fail(fmt::format("'{}': an empty texture coordinate index", r));
      }
    }
    if (form >= 0 && form != this_form) fail("the vertices of one statement mix forms (i, i/t, i//n, i/t/n)");
    form = this_form;
  }

  const std::string& path_;
  std::vector<std::string_view> words_;  // the current line's words
  uint64_t line_ = 0;
  uint64_t normals_ = 0, texcoords_ = 0;
  ObjSummary sum_;
};

}  // namespace

ObjSummary validate_obj(std::string_view bytes, const std::string& path, WorkProgress* progress) {
  ObjChecker check(path);
  uint64_t number = 0;
  size_t at = 0, next_report = 0;
  if (progress) progress->begin("checking", megabytes(bytes.size()), "MB");
  while (at < bytes.size()) {
    if (progress && at >= next_report) {
      progress->update(megabytes(at));
      next_report = at + kReportBytes;
    }
    size_t end = bytes.find('\n', at);
    if (end == std::string_view::npos) end = bytes.size();
    check.line(bytes.substr(at, end - at), ++number);
    at = end + 1;
  }
  return check.summary();
}

}  // namespace vbsim
