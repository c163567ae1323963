#include "render/png_file.h"

#include <stb/stb_image_write.h>

#include <stdexcept>
#include <string>

#include "io/atomic_output_file.h"

namespace vbsim {

namespace {

constexpr size_t kSignatureAndHeader = 8 + 25;  ///< PNG signature, then the IHDR chunk

void put_u32_be(std::vector<uint8_t>& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<uint8_t>(v >> shift));
}

/// An iTXt chunk: keyword, NUL, uncompressed, no language, no translated keyword, the text.
std::vector<uint8_t> itxt_chunk(const std::string& key, const std::string& text) {
  std::vector<uint8_t> body = {'i', 'T', 'X', 't'};
  body.insert(body.end(), key.begin(), key.end());
  body.insert(body.end(), {0, 0, 0, 0, 0});
  body.insert(body.end(), text.begin(), text.end());
  std::vector<uint8_t> chunk;
  put_u32_be(chunk, static_cast<uint32_t>(body.size() - 4));
  chunk.insert(chunk.end(), body.begin(), body.end());
  put_u32_be(chunk, png_crc32(body.data(), body.size()));
  return chunk;
}

}  // namespace

uint32_t png_crc32(const uint8_t* data, size_t size) {
  uint32_t crc = 0xffffffffu;
  for (size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xffffffffu;
}

void write_png_rgb(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb,
                   const std::string& note, const std::string& note_key) {
  if (width <= 0 || height <= 0 || rgb.size() != size_t(width) * size_t(height) * 3)
    throw std::runtime_error(path + ": image buffer does not match " + std::to_string(width) + "x" +
                             std::to_string(height));
  std::vector<uint8_t> png;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, rgb.data(), width * 3) ||
      png.size() < kSignatureAndHeader)
    throw std::runtime_error(path + ": cannot encode PNG image");
  if (!note.empty()) {
    const std::vector<uint8_t> chunk = itxt_chunk(note_key, note);
    png.insert(png.begin() + kSignatureAndHeader, chunk.begin(), chunk.end());
  }
  write_output_file(path, std::string(png.begin(), png.end()), "PNG image");
}

}  // namespace vbsim
