#include "harbour/io/ReliefImage.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

namespace harbour::io {
namespace {

constexpr int kGap_px = 6;

struct Rgb {
  unsigned char r, g, b;
};

// colour ramp for material height: dark ochre at the foot to pale at the top
Rgb ramp(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return {static_cast<unsigned char>(70 + 170 * t), static_cast<unsigned char>(55 + 150 * t),
          static_cast<unsigned char>(40 + 110 * t)};
}

// libpng with setjmp error handling, kept apart so no local of the caller can be clobbered by longjmp
void write_png(const std::string& path, const std::vector<Rgb>& pixels, const int width, const int height) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!file) throw std::runtime_error(path + ": cannot be written");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error(path + ": PNG encoding failed");
  }
  png_init_io(png, file.get());
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int row = 0; row < height; ++row)
    png_write_row(png, reinterpret_cast<png_const_bytep>(&pixels[static_cast<std::size_t>(row) * width]));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

}  // namespace

void write_relief_png(const std::string& path, std::span<const bulk::HeightGrid* const> grids,
                      int max_side_px) {
  // layout: each grid subsampled by an integer step so its longer side fits max_side_px
  std::vector<int> steps;
  int width = 0, height = 0;
  double top = 1e-9;
  for (const bulk::HeightGrid* g : grids) {
    const int step = std::max(1, (std::max(g->cells_x(), g->cells_y()) + max_side_px - 1) / max_side_px);
    steps.push_back(step);
    width += g->cells_x() / step + (width > 0 ? kGap_px : 0);
    height = std::max(height, g->cells_y() / step);
    top = std::max(top, g->max_height_m());
  }
  std::vector<Rgb> pixels(static_cast<std::size_t>(width) * height, Rgb{255, 255, 255});

  int x0 = 0;
  for (std::size_t n = 0; n < grids.size(); ++n) {
    const bulk::HeightGrid& g = *grids[n];
    const int step = steps[n], w = g.cells_x() / step, h = g.cells_y() / step;
    const double spacing = g.cell_size_m() * step;
    auto at = [&](int i, int j) {
      return g.height(std::clamp(i, 0, w - 1) * step, std::clamp(j, 0, h - 1) * step);
    };
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        // Lambert shading of the surface normal under a light from the north-west, 45 degrees up
        const double dzdx = (at(i + 1, j) - at(i - 1, j)) / (2 * spacing);
        const double dzdy = (at(i, j + 1) - at(i, j - 1)) / (2 * spacing);
        const double nx = -dzdx, ny = -dzdy, nz = 1.0, norm = std::sqrt(nx * nx + ny * ny + nz * nz);
        const double lx = -0.5, ly = 0.5, lz = std::sqrt(0.5);
        const double shade = std::clamp((nx * lx + ny * ly + nz * lz) / norm, 0.0, 1.0);
        const double z = at(i, j);
        const Rgb base = z > 1e-4 ? ramp(z / top) : Rgb{150, 150, 155};
        const double light = 0.35 + 0.65 * shade;
        // image rows run north (top) to south, so grid row j goes to image row h-1-j
        pixels[static_cast<std::size_t>(h - 1 - j) * width + x0 + i] = {
            static_cast<unsigned char>(base.r * light), static_cast<unsigned char>(base.g * light),
            static_cast<unsigned char>(base.b * light)};
      }
    x0 += w + kGap_px;
  }

  write_png(path, pixels, width, height);
}

}  // namespace harbour::io
