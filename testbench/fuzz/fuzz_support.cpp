#include "fuzz_support.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <systemc>  // declares sc_main, with C linkage

namespace vbsim::fuzz {

std::string input_file(const uint8_t* data, size_t size, const char* suffix) {
  static const std::string dir = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
  const std::string path = dir + "/vbsim_fuzz_" + std::to_string(::getpid()) + suffix;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "vbsim fuzz: cannot write the scratch file %s\n", path.c_str());
    std::abort();
  }
  return path;
}

}  // namespace vbsim::fuzz

// libsystemc.so brings a main() that calls sc_main(); libFuzzer's main() is the
// one these programs run, so this is never called.
int sc_main(int, char**) { return 0; }
