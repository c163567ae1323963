#include "structured_mutator.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace vbsim::fuzz {

namespace {

using Rng = std::mt19937;

/// Numbers at the limits the readers check.
const char* const kExtremeNumbers[] = {
    "3e38",  "3.4028235e38", "3.4028236e38", "3.40282357e38", "1e39",   "-1e39",  "1e-45",  "1.4e-45", "7e-46",
    "1e-46", "1.1754942e-38", "-0",          "-0.0",          "0",      "1e308",  "1.7976931348623157e308",
    "1e309", "-1e309",       "4.9e-324",     "1e-400",        "9223372036854775807", "9223372036854775808",
    "-9223372036854775808", "-9223372036854775809", "18446744073709551616", "2147483648", "-2147483649",
    "1e-30", "1e-35",        "1e18",         "1.2e18",        "1e99999999999", "0.5e-99999999", ".5",   "5.",
};

bool is_number_start(uint8_t c) { return c == '-' || (c >= '0' && c <= '9'); }
bool is_number_char(uint8_t c) {
  return is_number_start(c) || c == '.' || c == 'e' || c == 'E' || c == '+';
}

/// Where the numbers (outside strings), the values after ':' ',' '[' and the
/// "key": value members start: one pass, linear in the input (the fuzzer's
/// inputs are up to 64 KiB of brackets); a value's end is found only for the
/// one a mutation picks.
struct JsonMarks {
  std::vector<std::pair<size_t, size_t>> numbers;  ///< [begin, end)
  std::vector<size_t> values;                      ///< first byte of a value
  std::vector<std::pair<size_t, size_t>> members;  ///< key's opening quote, first byte of its value
};

/// End of the value starting at `i` (a scalar, a string or a balanced container).
size_t value_end(const std::string& s, size_t i) {
  if (i >= s.size()) return i;
  if (s[i] == '"') {
    for (size_t k = i + 1; k < s.size(); ++k) {
      if (s[k] == '\\') ++k;
      else if (s[k] == '"') return k + 1;
    }
    return s.size();
  }
  if (s[i] == '[' || s[i] == '{') {
    int depth = 0;
    bool in_string = false;
    for (size_t k = i; k < s.size(); ++k) {
      const char c = s[k];
      if (in_string) {
        if (c == '\\') ++k;
        else if (c == '"') in_string = false;
      } else if (c == '"') {
        in_string = true;
      } else if (c == '[' || c == '{') {
        ++depth;
      } else if ((c == ']' || c == '}') && --depth == 0) {
        return k + 1;
      }
    }
    return s.size();
  }
  size_t k = i;
  while (k < s.size() && s[k] != ',' && s[k] != '}' && s[k] != ']' && s[k] != '\n') ++k;
  return k;
}

JsonMarks mark_json(const std::string& s) {
  JsonMarks m;
  bool in_string = false;
  size_t string_start = 0;
  size_t last_string = std::string::npos;  ///< opening quote of the latest string, while only blanks follow it
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') {
        in_string = false;
        last_string = string_start;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
      string_start = i;
      continue;
    }
    if (c == ':' || c == ',' || c == '[') {
      size_t k = i + 1;
      while (k < s.size() && s[k] == ' ') ++k;
      if (k < s.size() && s[k] != ']' && s[k] != '}') {
        m.values.push_back(k);
        if (c == ':' && last_string != std::string::npos) m.members.emplace_back(last_string, k);
      }
    }
    if (c != ' ') last_string = std::string::npos;
    if (is_number_start(static_cast<uint8_t>(c)) && (i == 0 || !is_number_char(static_cast<uint8_t>(s[i - 1])))) {
      size_t k = i;
      while (k < s.size() && is_number_char(static_cast<uint8_t>(s[k]))) ++k;
      m.numbers.emplace_back(i, k);
      i = k - 1;
    }
  }
  return m;
}

/// Depth of a nesting mutation: mostly small, sometimes far beyond any limit.
size_t nesting_depth(Rng& rng) {
  static const size_t kDepths[] = {1, 2, 63, 64, 65, 100, 1000, 30000, 100000};
  return kDepths[rng() % (sizeof kDepths / sizeof kDepths[0])];
}

bool mutate_json(std::string& s, size_t max_size, Rng& rng) {
  const JsonMarks m = mark_json(s);
  switch (rng() % 3) {
    case 0: {  // nesting
      if (m.values.empty()) return false;
      const size_t b = m.values[rng() % m.values.size()];
      const size_t e = value_end(s, b);
      const bool arrays = rng() % 2 == 0;
      const std::string open = arrays ? "[" : "{\"k\":", close = arrays ? "]" : "}";
      const size_t room = max_size > s.size() ? (max_size - s.size()) / (open.size() + close.size()) : 0;
      const size_t depth = std::min(nesting_depth(rng), room);
      if (depth == 0) return false;
      std::string wrapped;
      wrapped.reserve(s.size() + depth * (open.size() + close.size()));
      wrapped.append(s, 0, b);
      for (size_t k = 0; k < depth; ++k) wrapped += open;
      wrapped.append(s, b, e - b);
      for (size_t k = 0; k < depth; ++k) wrapped += close;
      wrapped.append(s, e, std::string::npos);
      s.swap(wrapped);
      return true;
    }
    case 1: {  // an extreme number
      if (m.numbers.empty()) return false;
      const auto [b, e] = m.numbers[rng() % m.numbers.size()];
      const char* number = kExtremeNumbers[rng() % (sizeof kExtremeNumbers / sizeof kExtremeNumbers[0])];
      if (s.size() - (e - b) + std::strlen(number) > max_size) return false;
      s.replace(b, e - b, number);
      return true;
    }
    default: {  // a repeated key
      if (m.members.empty()) return false;
      const auto [b, value] = m.members[rng() % m.members.size()];
      const size_t e = value_end(s, value);
      const std::string member = s.substr(b, e - b);
      if (s.size() + member.size() + 1 > max_size) return false;
      s.insert(e, "," + member);
      return true;
    }
  }
}

/// A count near, beyond or inside `truth`.
uint64_t lying_count(uint64_t truth, Rng& rng) {
  switch (rng() % 6) {
    case 0: return truth + 1 + rng() % 8;
    case 1: return truth > 0 ? truth - 1 - rng() % std::min<uint64_t>(truth, 8) : 1;
    case 2: return truth + 96;  // a binary trace's next record
    case 3: return 0;
    case 4: return 0xffffffffu;
    default: return truth * 2 + 1;
  }
}

bool mutate_binary_trace(std::string& s, Rng& rng) {
  if (s.size() < 16) return false;
  uint32_t n = 0;
  std::memcpy(&n, s.data() + 12, 4);  // little-endian hosts only, as the fuzz build
  if (rng() % 4 == 0) {  // an extreme number in the header JSON
    std::string header = s.substr(16, std::min<size_t>(n, s.size() - 16));
    if (!mutate_json(header, header.size() + 64, rng)) return false;
    const uint32_t len = static_cast<uint32_t>(header.size());
    const size_t padded = (n + 7u) / 8u * 8u;
    std::string out = s.substr(0, 12);
    out.append(reinterpret_cast<const char*>(&len), 4);
    out += header;
    out.append((len + 7u) / 8u * 8u - len, ' ');
    if (16 + padded <= s.size()) out.append(s, 16 + padded, std::string::npos);
    s.swap(out);
    return true;
  }
  const uint32_t lie = static_cast<uint32_t>(lying_count(n, rng));
  std::memcpy(s.data() + 12, &lie, 4);
  return true;
}

bool mutate_ply(std::string& s, Rng& rng) {
  const size_t header_end = s.find("end_header");
  if (header_end == std::string::npos) return false;
  std::vector<std::pair<size_t, size_t>> counts;  // digits after "element NAME "
  for (size_t at = s.find("element "); at != std::string::npos && at < header_end; at = s.find("element ", at + 1)) {
    const size_t name_end = s.find(' ', at + 8);
    if (name_end == std::string::npos || name_end > header_end) continue;
    size_t k = name_end + 1;
    while (k < s.size() && s[k] >= '0' && s[k] <= '9') ++k;
    if (k > name_end + 1) counts.emplace_back(name_end + 1, k);
  }
  if (counts.empty() || rng() % 3 == 0) {  // an extreme number in an ascii body
    JsonMarks m = mark_json(s.substr(header_end));
    if (m.numbers.empty()) return false;
    auto [b, e] = m.numbers[rng() % m.numbers.size()];
    const char* number = kExtremeNumbers[rng() % (sizeof kExtremeNumbers / sizeof kExtremeNumbers[0])];
    s.replace(header_end + b, e - b, number);
    return true;
  }
  const auto [b, e] = counts[rng() % counts.size()];
  // Saturates at 2^64 - 1 for a count beyond it (a count the fuzzer grew).
  const uint64_t truth = std::strtoull(s.substr(b, e - b).c_str(), nullptr, 10);
  s.replace(b, e - b, std::to_string(lying_count(truth, rng)));
  return true;
}

}  // namespace

size_t structured_mutate(InputFormat format, uint8_t* data, size_t size, size_t max_size, unsigned seed,
                         ByteMutator bytes) {
  Rng rng(seed);
  // One call in four is libFuzzer's own: byte mutations still explore the rest.
  if (rng() % 4 != 0) {
    std::string s(reinterpret_cast<const char*>(data), size);
    bool changed = false;
    switch (format) {
      case InputFormat::JsonLines: {
        // One line of the file, mutated as a JSON document.
        std::vector<size_t> starts = {0};
        for (size_t i = 0; i + 1 < s.size(); ++i)
          if (s[i] == '\n') starts.push_back(i + 1);
        const size_t b = starts[rng() % starts.size()];
        size_t e = s.find('\n', b);
        if (e == std::string::npos) e = s.size();
        std::string line = s.substr(b, e - b);
        const size_t room = max_size > s.size() - line.size() ? max_size - (s.size() - line.size()) : 0;
        changed = mutate_json(line, room, rng);
        if (changed) s.replace(b, e - b, line);
        break;
      }
      case InputFormat::Json: changed = mutate_json(s, max_size, rng); break;
      case InputFormat::BinaryTrace: changed = mutate_binary_trace(s, rng); break;
      case InputFormat::Ply:
      case InputFormat::Obj: changed = format == InputFormat::Ply ? mutate_ply(s, rng) : mutate_json(s, max_size, rng); break;
    }
    if (changed && s.size() <= max_size) {
      std::memcpy(data, s.data(), s.size());
      return s.size();
    }
  }
  return bytes ? bytes(data, size, max_size) : size;
}

}  // namespace vbsim::fuzz
