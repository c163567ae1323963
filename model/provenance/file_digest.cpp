#include "provenance/file_digest.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace vbsim {

namespace {

struct DigestContext {
  DigestContext() : ctx(EVP_MD_CTX_new()) {
    if (!ctx || EVP_DigestInit_ex(ctx, EVP_sha256(), nullptr) != 1)
      throw std::runtime_error("SHA-256: cannot initialise libcrypto's digest");
  }
  ~DigestContext() { EVP_MD_CTX_free(ctx); }
  void update(const void* data, size_t size) {
    if (EVP_DigestUpdate(ctx, data, size) != 1) throw std::runtime_error("SHA-256: digest update failed");
  }
  std::string hex() {
    unsigned char md[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    if (EVP_DigestFinal_ex(ctx, md, &len) != 1) throw std::runtime_error("SHA-256: digest failed");
    std::string out;
    for (unsigned int i = 0; i < len; ++i) out += fmt::format("{:02x}", md[i]);
    return out;
  }
  EVP_MD_CTX* ctx;
};

}  // namespace

std::string sha256_hex(const void* data, size_t size) {
  DigestContext d;
  d.update(data, size);
  return d.hex();
}

FileDigest sha256_file(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) throw std::runtime_error(fmt::format("{}: cannot read for its checksum: {}", path, std::strerror(errno)));
  DigestContext d;
  std::vector<char> block(1 << 20);
  FileDigest out;
  for (size_t n; (n = std::fread(block.data(), 1, block.size(), f.get())) > 0;) {
    d.update(block.data(), n);
    out.bytes += n;
  }
  if (std::ferror(f.get())) throw std::runtime_error(fmt::format("{}: read error while computing its checksum", path));
  out.sha256 = d.hex();
  return out;
}

}  // namespace vbsim
