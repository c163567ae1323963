// Reading a whole JSON document that a user hands over (a --config file, a
// stats file read back, a score table to merge): the bounds every such reader
// shares, so that no file can crash vbsim or be read with a silent choice.
//
// Contract of parse_json_document:
//   - nesting deeper than kMaxJsonDepth arrays and objects is refused before
//     the document is parsed (a deep document would otherwise exhaust the
//     stack of the recursive code that walks or prints it);
//   - a key that appears twice in one object is refused (plain parsing keeps
//     the last one silently; the trace readers refuse it too);
//   - malformed JSON, numbers beyond double and numbers that are not zero but
//     round to 0 in double (1e-999) are refused;
//   - every refusal is a JsonDocumentError whose message starts with
//     "ORIGIN:" and names the line of the fault (a duplicate key or a number
//     that rounds to 0: its path, "hw.memory.l1").
// read_json_text reads at most kMaxJsonDocumentBytes of a file.
#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace vbsim {

/// Deepest nesting of arrays and objects any JSON input may have (vbsim's own
/// documents nest at most 6 levels; a trace line 2).
constexpr int kMaxJsonDepth = 64;

/// Largest JSON document read from a file (a configuration, a technology
/// file, a score table, a manifest): 64 MiB. vbsim's own are below 1 MiB; an
/// endless input (/dev/zero) is refused when it passes the limit, before
/// memory grows with it.
constexpr std::size_t kMaxJsonDocumentBytes = std::size_t{64} << 20;

struct JsonDocumentError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Where `text` first nests deeper than `limit` (its byte offset), or npos.
/// Brackets inside strings do not count; the text need not be valid JSON.
std::size_t json_nesting_overflow(std::string_view text, int limit = kMaxJsonDepth);

/// 1-based line of byte `offset` in `text`.
std::size_t line_of_offset(std::string_view text, std::size_t offset);

/// Parses `text` under the contract above; `origin` names it in errors (a path).
nlohmann::json parse_json_document(std::string_view text, const std::string& origin);

/// The bytes of the file at `path` (a pipe too), read once: a
/// JsonDocumentError "PATH: ..." when it is a directory, cannot be opened or
/// read, or holds more than `limit` bytes (then it stops reading there).
std::string read_json_text(const std::string& path, std::size_t limit = kMaxJsonDocumentBytes);

/// Reads the file at `path` whole (read_json_text) and parses it (errors name the path).
nlohmann::json read_json_document(const std::string& path);

}  // namespace vbsim
