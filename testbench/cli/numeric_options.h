// Numbers on the command line, checked as strictly as a configuration's
// (README "Conventions"; docs/config.md): CLI11 2.1 converts with strtoull,
// strtoll and strtold and keeps what they return, so `-1` for an unsigned
// option became 18446744073709551615, a value beyond 64 bits the largest one,
// `010` eight and `1e-999` zero. Every option of every command is checked
// here, by the type CLI11 names it with, once the command line is parsed and
// before the command runs; a value refused is a usage error naming the option.
#pragma once
#include <CLI/CLI.hpp>
#include <string>

namespace vbsim::cli {

/// Why `text` is no value of an option of CLI11's type `type_name` ("UINT",
/// "INT", "FLOAT"), or "" when it is one (or the type is not a number):
///   UINT   a decimal integer from 0 to 2^64 - 1 (no minus sign, no 0x, no
///          leading 0, which CLI11 would read as octal)
///   INT    a decimal integer from -2^63 to 2^63 - 1 (no 0x, no leading 0)
///   FLOAT  a finite decimal number within double that does not round to 0
///          unless it is 0 (float32 options are checked again where they are
///          used, as the configuration field they set: method_options.h)
/// Narrower integer types are checked by CLI11 itself (a value that does not
/// fit is its conversion error).
std::string numeric_value_problem(const std::string& type_name, const std::string& text);

/// Throws UsageError "option '--seed': ..." for the first value of an option
/// of the subcommands parsed that numeric_value_problem refuses.
void check_numeric_option_values(const CLI::App& app);

}  // namespace vbsim::cli
