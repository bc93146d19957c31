#pragma once

#include <cstdint>
#include <vector>

namespace osg {
class Image;
}

namespace harbour::ig {

/// An RGB (or RGBA) picture as OpenGL reads it (bottom row first) encoded as a baseline JPEG (libjpeg) at
/// `quality` (1-100): the instructor's view of a station's cab, small enough to stream.
std::vector<std::uint8_t> encode_jpeg(const osg::Image& image, int quality = 70);

}  // namespace harbour::ig
