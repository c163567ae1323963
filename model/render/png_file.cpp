#include "render/png_file.h"

#include <stb/stb_image_write.h>

#include <stdexcept>

namespace vbsim {

void write_png_rgb(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != size_t(width) * size_t(height) * 3)
    throw std::runtime_error(path + ": image buffer does not match " + std::to_string(width) + "x" +
                             std::to_string(height));
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3))
    throw std::runtime_error(path + ": cannot write PNG image");
}

}  // namespace vbsim
