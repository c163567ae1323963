// Writing RGB images as PNG with stb_image_write. Debian's libstb-dev ships the
// stb headers and a precompiled libstb (every *_IMPLEMENTATION already built,
// as its README.Debian asks users to link rather than compile their own), so
// vbsim links libstb (pkg-config `stb`) and defines no implementation macro.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace vbsim {

/// Writes `rgb` (width * height * 3 bytes, row-major, top row first) to `path`.
/// Throws std::runtime_error naming `path` when it cannot be written.
void write_png_rgb(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb);

}  // namespace vbsim
