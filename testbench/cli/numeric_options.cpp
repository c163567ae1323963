#include "numeric_options.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "exit_codes.h"

namespace vbsim::cli {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// `text` is [sign] digits, with a sign only when `sign_allowed`.
bool is_decimal_integer(const std::string& text, bool sign_allowed) {
  std::size_t i = 0;
  if (sign_allowed && (text[0] == '-' || text[0] == '+')) i = 1;
  if (i == text.size()) return false;
  for (; i < text.size(); ++i)
    if (!is_digit(text[i])) return false;
  return true;
}

/// A leading 0 before more digits: CLI11 reads the number as octal (010 is 8).
bool has_leading_zero(const std::string& text) {
  const std::size_t i = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
  return text.size() > i + 1 && text[i] == '0';
}

/// `text` is [sign] digits [. digits] [e [sign] digits], with a digit in the
/// mantissa; `nonzero` says whether one of the mantissa's digits is not 0.
bool is_decimal_number(const std::string& text, bool& nonzero) {
  std::size_t i = 0;
  nonzero = false;
  if (i < text.size() && (text[i] == '-' || text[i] == '+')) ++i;
  std::size_t digits = 0;
  for (; i < text.size() && is_digit(text[i]); ++i, ++digits) nonzero = nonzero || text[i] != '0';
  if (i < text.size() && text[i] == '.')
    for (++i; i < text.size() && is_digit(text[i]); ++i, ++digits) nonzero = nonzero || text[i] != '0';
  if (digits == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '-' || text[i] == '+')) ++i;
    std::size_t exponent_digits = 0;
    for (; i < text.size() && is_digit(text[i]); ++i) ++exponent_digits;
    if (exponent_digits == 0) return false;
  }
  return i == text.size();
}

}  // namespace

std::string numeric_value_problem(const std::string& type_name, const std::string& text) {
  if (text.empty()) return "";  // refused as an empty value (main.cpp)
  if (type_name == "UINT") {
    if (text[0] == '-') return fmt::format("{} is negative: it takes an integer from 0 to {}", text, UINT64_MAX);
    const std::string digits = text[0] == '+' ? text.substr(1) : text;
    if (!is_decimal_integer(digits, false)) return fmt::format("'{}' is not a decimal integer", text);
    if (has_leading_zero(digits)) return fmt::format("'{}' has a leading 0 (write it without: 0N reads as octal)", text);
    errno = 0;
    std::strtoull(digits.c_str(), nullptr, 10);
    if (errno == ERANGE) return fmt::format("{} is out of range: it takes an integer from 0 to {}", text, UINT64_MAX);
  } else if (type_name == "INT") {
    if (!is_decimal_integer(text, true)) return fmt::format("'{}' is not a decimal integer", text);
    if (has_leading_zero(text)) return fmt::format("'{}' has a leading 0 (write it without: 0N reads as octal)", text);
    errno = 0;
    std::strtoll(text.c_str(), nullptr, 10);
    if (errno == ERANGE)
      return fmt::format("{} is out of range: it takes an integer from {} to {}", text, INT64_MIN, INT64_MAX);
  } else if (type_name == "FLOAT") {
    bool nonzero = false;
    if (!is_decimal_number(text, nonzero)) return fmt::format("'{}' is not a decimal number", text);
    errno = 0;
    const double x = std::strtod(text.c_str(), nullptr);
    if (!std::isfinite(x))
      return fmt::format("{} is out of range for a double (largest {:g})", text, std::numeric_limits<double>::max());
    if (x == 0.0 && nonzero) return fmt::format("{} is too small for a double: it rounds to 0", text);
  }
  return "";
}

void check_numeric_option_values(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands())
    for (const CLI::Option* opt : sub->get_options()) {
      if (opt->get_type_size() == 0) continue;  // a flag
      // The type's name, without the validators' descriptions CLI11 appends ("INT:INT in [1 - 9]").
      const std::string full = opt->get_type_name();
      const std::string type = full.substr(0, full.find(':'));
      for (const std::string& value : opt->results()) {
        const std::string problem = numeric_value_problem(type, value);
        if (problem.empty()) continue;
        throw UsageError(opt->get_positional() ? fmt::format("argument '{}': {}", opt->get_name(true), problem)
                                               : fmt::format("option '{}': {}", opt->get_name(), problem));
      }
    }
}

}  // namespace vbsim::cli
