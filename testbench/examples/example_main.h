// The examples' sc_main: runs the example's `run` and turns an exception into
// a message on stderr, "NAME: what", and exit status 1.
#pragma once
#include <cstdio>
#include <exception>

namespace vbsim_examples {

inline int run_example(const char* name, int (*run)(int, char**), int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
}

}  // namespace vbsim_examples
