#include "trace/trace_ray_count.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "trace/binary_trace_format.h"

namespace vbsim {

namespace {

uint32_t read_u32_le(const unsigned char* p) { return p[0] | p[1] << 8 | p[2] << 16 | uint32_t(p[3]) << 24; }

}  // namespace

uint64_t count_trace_rays(const std::string& path) {
  // A pipe can be read once: the replay's own reading of it comes first.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return 0;
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) return 0;
  unsigned char pre[kBinaryTracePreambleBytes];
  const size_t got = std::fread(pre, 1, sizeof pre, f.get());
  if (got == sizeof pre && std::memcmp(pre, kBinaryTraceMagic, sizeof kBinaryTraceMagic) == 0) {
    const uint64_t header = read_u32_le(pre + 12);
    const uint64_t first_record = kBinaryTracePreambleBytes + (header + 7) / 8 * 8;
    if (std::fseek(f.get(), 0, SEEK_END) != 0) return 0;
    const long size = std::ftell(f.get());
    const uint64_t record = binary_trace_record_bytes(read_u32_le(pre + 8));
    return size > 0 && uint64_t(size) > first_record ? (uint64_t(size) - first_record) / record : 0;
  }
  // Text: count lines whose first non-blank character exists and is not '#'.
  std::rewind(f.get());
  std::vector<char> block(1 << 20);
  uint64_t lines = 0;
  bool at_line_start = true;  // no non-blank character on this line yet
  for (size_t n; (n = std::fread(block.data(), 1, block.size(), f.get())) > 0;) {
    for (size_t i = 0; i < n; ++i) {
      const char c = block[i];
      if (c == '\n') {
        at_line_start = true;
      } else if (at_line_start && c != ' ' && c != '\t' && c != '\r') {
        at_line_start = false;
        lines += c != '#';
      }
    }
  }
  return lines > 0 ? lines - 1 : 0;  // the first counted line is the header
}

}  // namespace vbsim
