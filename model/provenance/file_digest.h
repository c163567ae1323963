// SHA-256 digests of files and byte strings (OpenSSL's libcrypto), as
// lowercase hex: the same text `sha256sum` prints, so a recorded checksum can
// be checked by hand.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace vbsim {

/// SHA-256 of `size` bytes at `data`.
std::string sha256_hex(const void* data, size_t size);

/// SHA-256 of a file's bytes, read in 1 MiB blocks, and its size in bytes.
/// Throws std::runtime_error naming the file when it cannot be read.
struct FileDigest {
  std::string sha256;
  uint64_t bytes = 0;
};
FileDigest sha256_file(const std::string& path);

}  // namespace vbsim
