// Writing RGB images as PNG with stb_image_write. Debian's libstb-dev ships the
// stb headers and a precompiled libstb (every *_IMPLEMENTATION already built,
// as its README.Debian asks users to link rather than compile their own), so
// vbsim links libstb (pkg-config `stb`) and defines no implementation macro.
// A text note (the provenance) goes into an iTXt chunk right after IHDR, which
// every PNG reader skips or shows as metadata (`exiftool`, PIL's `img.text`).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace vbsim {

/// Writes `rgb` (width * height * 3 bytes, row-major, top row first) to `path`,
/// with `note` (UTF-8, may be empty: none) as iTXt keyword `note_key`.
/// Throws std::runtime_error naming `path` when it cannot be written.
void write_png_rgb(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb,
                   const std::string& note = "", const std::string& note_key = "vbsim-provenance");

/// The CRC-32 of PNG chunks (ISO 3309 polynomial, as in the PNG specification).
uint32_t png_crc32(const uint8_t* data, size_t size);

}  // namespace vbsim
