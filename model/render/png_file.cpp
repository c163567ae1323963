#include "render/png_file.h"

#include <stb/stb_image_write.h>

#include <stdexcept>
#include <string>

#include "io/atomic_output_file.h"

namespace vbsim {

void write_png_rgb(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != size_t(width) * size_t(height) * 3)
    throw std::runtime_error(path + ": image buffer does not match " + std::to_string(width) + "x" +
                             std::to_string(height));
  std::string png;
  const auto append = [](void* out, void* data, int size) {
    static_cast<std::string*>(out)->append(static_cast<const char*>(data), static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, rgb.data(), width * 3))
    throw std::runtime_error(path + ": cannot encode PNG image");
  write_output_file(path, png, "PNG image");
}

}  // namespace vbsim
