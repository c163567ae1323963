// The examples' output (testbench/examples/): "key value" lines, run as a
// user runs them.
#pragma once
#include <map>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "run_vbsim.h"

namespace vbsim::test {

using ExampleFields = std::map<std::string, std::string>;

/// Runs the example program `binary` with `args`; requires exit status 0 and
/// the key `required` among its "key value" lines.
inline ExampleFields run_example_program(const std::string& binary, const std::string& args,
                                         const std::string& required) {
  const RunResult r = run_command("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1 " + binary + " " + args + " 2>&1");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  ExampleFields f;  // a line is "key value"; the value runs to the end of the line (a path may hold spaces)
  std::istringstream in(r.output);
  std::string line;
  while (std::getline(in, line))
    if (const size_t space = line.find(' '); space != std::string::npos) f[line.substr(0, space)] = line.substr(space + 1);
  REQUIRE(f.count(required));
  return f;
}

inline uint64_t field_u64(const ExampleFields& f, const std::string& key) { return std::stoull(f.at(key)); }
inline double field_double(const ExampleFields& f, const std::string& key) { return std::stod(f.at(key)); }

}  // namespace vbsim::test
