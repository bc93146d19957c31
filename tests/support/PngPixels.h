#pragma once

// A PNG file's pixels as 8-bit RGB, row after row from the top (libpng's simplified API), for tests that
// measure pictures the programs wrote.

#include <png.h>

#include <optional>
#include <string>
#include <vector>

namespace harbour::test {

struct RgbPixels {
  int width = 0, height = 0;
  std::vector<png_byte> rgb;  ///< 3 bytes a pixel
};

/// nullopt where the file cannot be read as a PNG
inline std::optional<RgbPixels> read_png_rgb(const std::string& file) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, file.c_str())) return std::nullopt;
  image.format = PNG_FORMAT_RGB;
  RgbPixels out{static_cast<int>(image.width), static_cast<int>(image.height),
                std::vector<png_byte>(PNG_IMAGE_SIZE(image))};
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) return std::nullopt;
  return out;
}

}  // namespace harbour::test
