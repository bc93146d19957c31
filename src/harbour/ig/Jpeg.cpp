#include "harbour/ig/Jpeg.h"

#include <osg/Image>

#include <cstdio>
#include <stdexcept>
#include <vector>

#include <jpeglib.h>

namespace harbour::ig {

std::vector<std::uint8_t> encode_jpeg(const osg::Image& image, int quality) {
  const int pixel_bytes = static_cast<int>(image.getPixelSizeInBits() / 8);
  if (image.s() <= 0 || image.t() <= 0 || (pixel_bytes != 3 && pixel_bytes != 4))
    throw std::invalid_argument("encode_jpeg: an RGB or RGBA picture");
  jpeg_compress_struct cinfo{};
  jpeg_error_mgr errors{};
  cinfo.err = jpeg_std_error(&errors);
  errors.error_exit = [](j_common_ptr) { throw std::runtime_error("libjpeg could not encode the picture"); };
  jpeg_create_compress(&cinfo);
  unsigned char* out = nullptr;
  unsigned long out_bytes = 0;
  jpeg_mem_dest(&cinfo, &out, &out_bytes);
  cinfo.image_width = static_cast<JDIMENSION>(image.s());
  cinfo.image_height = static_cast<JDIMENSION>(image.t());
  cinfo.input_components = 3;
  cinfo.in_color_space = JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, quality, TRUE);
  std::vector<std::uint8_t> row(static_cast<std::size_t>(image.s()) * 3);
  try {
    jpeg_start_compress(&cinfo, TRUE);
    while (cinfo.next_scanline < cinfo.image_height) {
      // JPEG's rows run from the top: OpenGL's last row first
      const int source_row = image.t() - 1 - static_cast<int>(cinfo.next_scanline);
      const unsigned char* p = image.data(0, source_row);
      for (int x = 0; x < image.s(); ++x)
        for (int c = 0; c < 3; ++c)
          row[static_cast<std::size_t>(3 * x + c)] = p[pixel_bytes * x + c];
      JSAMPROW rows[] = {row.data()};
      jpeg_write_scanlines(&cinfo, rows, 1);
    }
    jpeg_finish_compress(&cinfo);
  } catch (...) {
    jpeg_destroy_compress(&cinfo);
    std::free(out);
    throw;
  }
  std::vector<std::uint8_t> bytes(out, out + out_bytes);
  jpeg_destroy_compress(&cinfo);
  std::free(out);
  return bytes;
}

}  // namespace harbour::ig
