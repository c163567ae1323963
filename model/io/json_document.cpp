#include "io/json_document.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <unordered_set>
#include <vector>

#include <fmt/format.h>

namespace vbsim {

namespace {

using json = nlohmann::json;

/// Whether a JSON number's digits before its exponent are not all 0.
bool mantissa_is_nonzero(const std::string& number) {
  for (const char c : number) {
    if (c == 'e' || c == 'E') break;
    if (c >= '1' && c <= '9') return true;
  }
  return false;
}

/// nlohmann's DOM builder with two rules added: a key met twice in one object
/// stops the parse (the DOM builder alone would keep the last value).
class DocumentSax {
 public:
  explicit DocumentSax(json& root) : dom_(root, /*allow_exceptions=*/false) {}

  bool null() { return dom_.null(); }
  bool boolean(bool v) { return dom_.boolean(v); }
  bool number_integer(json::number_integer_t v) { return dom_.number_integer(v); }
  bool number_unsigned(json::number_unsigned_t v) { return dom_.number_unsigned(v); }
  bool number_float(json::number_float_t v, const std::string& s) {
    if (v == 0 && mantissa_is_nonzero(s)) {  // 1e-999: not zero, but read as 0
      underflow_ = path_.empty() ? "<root>" : path_;
      underflow_text_ = s;
      return false;
    }
    return dom_.number_float(v, s);
  }
  bool string(std::string& v) { return dom_.string(v); }
  bool binary(json::binary_t& v) { return dom_.binary(v); }
  bool start_object(std::size_t n) {
    scopes_.push_back(Scope{true, {}, path_.size()});
    return dom_.start_object(n);
  }
  bool start_array(std::size_t n) {
    scopes_.push_back(Scope{false, {}, path_.size()});
    return dom_.start_array(n);
  }
  bool end_object() { return close() && dom_.end_object(); }
  bool end_array() { return close() && dom_.end_array(); }
  bool key(std::string& k) {
    Scope& scope = scopes_.back();
    path_.resize(scope.path_length);
    if (!path_.empty()) path_ += '.';
    path_ += k;
    if (!scope.keys.insert(k).second) {
      duplicate_ = path_;
      return false;
    }
    return dom_.key(k);
  }
  bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e) {
    error_position_ = position;
    error_ = e.what();
    return dom_.parse_error(position, token, e);
  }

  const std::string& duplicate() const { return duplicate_; }
  const std::string& underflow() const { return underflow_; }
  const std::string& underflow_text() const { return underflow_text_; }
  const std::string& error() const { return error_; }
  std::size_t error_position() const { return error_position_; }

 private:
  struct Scope {
    bool object;
    std::unordered_set<std::string> keys;
    std::size_t path_length;  ///< length of path_ outside this container
  };
  bool close() {
    path_.resize(scopes_.back().path_length);
    scopes_.pop_back();
    return true;
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  std::vector<Scope> scopes_;
  std::string path_;  ///< key path of the value being read, "a.b"
  std::string duplicate_;
  std::string underflow_, underflow_text_;  ///< a number that rounds to 0 in double, and its text
  std::string error_;
  std::size_t error_position_ = 0;
};

/// nlohmann's message without its "[json.exception.parse_error.101] parse error at line 1, column 5: " prefix.
std::string plain_message(const std::string& what) {
  std::string w = what;
  const std::size_t tag = w.find("] ");
  if (tag != std::string::npos) w = w.substr(tag + 2);
  const std::size_t column = w.find("column ");
  if (column != std::string::npos) {
    const std::size_t colon = w.find(": ", column);
    if (colon != std::string::npos) w = w.substr(colon + 2);
  }
  return w;
}

}  // namespace

std::size_t json_nesting_overflow(std::string_view text, int limit) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;  // the escaped character cannot end the string
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::string_view::npos;
}

std::size_t line_of_offset(std::string_view text, std::size_t offset) {
  const std::size_t end = offset < text.size() ? offset : text.size();
  std::size_t line = 1;
  for (std::size_t i = 0; i < end; ++i) line += text[i] == '\n';
  return line;
}

json parse_json_document(std::string_view text, const std::string& origin) {
  if (const std::size_t at = json_nesting_overflow(text); at != std::string_view::npos)
    throw JsonDocumentError(fmt::format("{}: line {}: JSON nested deeper than {} levels of arrays and objects",
                                        origin, line_of_offset(text, at), kMaxJsonDepth));
  json value;
  DocumentSax sax(value);
  const bool ok = json::sax_parse(text.begin(), text.end(), &sax, json::input_format_t::json, true);
  if (!sax.duplicate().empty())
    throw JsonDocumentError(fmt::format("{}: field '{}': appears twice", origin, sax.duplicate()));
  if (!sax.underflow().empty())
    throw JsonDocumentError(fmt::format("{}: field '{}': {} is too small for a double: it rounds to 0", origin,
                                        sax.underflow(), sax.underflow_text()));
  if (!ok || !sax.error().empty()) {
    // nlohmann counts the failing character's position from 1.
    const std::size_t at = sax.error_position() > 0 ? sax.error_position() - 1 : 0;
    throw JsonDocumentError(fmt::format("{}: line {}: not valid JSON: {}", origin, line_of_offset(text, at),
                                        plain_message(sax.error())));
  }
  return value;
}

std::string read_json_text(const std::string& path, std::size_t limit) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw JsonDocumentError(fmt::format("{}: is a directory, not a JSON file", path));
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw JsonDocumentError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  std::string text;
  char block[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, block, sizeof block);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw JsonDocumentError(fmt::format("{}: read error: {}", path, std::strerror(err)));
    }
    if (n == 0) break;
    if (text.size() + static_cast<std::size_t>(n) > limit) {
      ::close(fd);
      throw JsonDocumentError(fmt::format("{}: longer than {} MiB, the limit of a JSON file (docs/config.md)", path,
                                          limit >> 20));
    }
    text.append(block, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return text;
}

json read_json_document(const std::string& path) { return parse_json_document(read_json_text(path), path); }

}  // namespace vbsim
