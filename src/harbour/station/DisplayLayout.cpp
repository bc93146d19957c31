#include "harbour/station/DisplayLayout.h"

#include <algorithm>
#include <cmath>

namespace harbour::station {

DisplayLayout layout_displays(const Profile& profile, int max_width) {
  DisplayLayout layout;
  if (profile.displays.empty()) return layout;  // every display drawn elsewhere
  const DisplayChannel& first = profile.displays.front();
  const int channels = static_cast<int>(profile.displays.size());
  const int tile_width = std::min(first.width, max_width / channels);
  const int height = std::min(
      1080, static_cast<int>(std::lround(static_cast<double>(tile_width) * first.height / first.width)));
  const bool shared = profile.windows == Profile::Windows::kShared;
  if (shared)
    layout.windows.push_back({tile_width * channels, height, 0});
  else
    for (int c = 0; c < channels; ++c)
      layout.windows.push_back({tile_width, height, c});
  const bool side_by_side = profile.stereo && profile.stereo->mode == Profile::Stereo::Mode::kSideBySide;
  layout.render_width = side_by_side ? tile_width / 2 : tile_width;
  layout.render_height = height;
  for (int c = 0; c < channels; ++c) {
    DisplayLayout::Picture picture;
    picture.channel = c;
    picture.window = shared ? 0 : c;
    picture.x0 = shared ? c * tile_width : 0;
    if (!profile.stereo) {
      layout.pictures.push_back(picture);
      continue;
    }
    const double half = profile.stereo->eye_separation_m / 2.0;
    DisplayLayout::Picture left = picture, right = picture;
    left.eye_offset_m = -half;
    right.eye_offset_m = half;
    if (side_by_side) {
      left.pixel_aspect = right.pixel_aspect = 2.0;
      right.x0 += layout.render_width;
    } else {  // anaglyph: red for the left eye, cyan for the right
      left.colours = 0b100;
      right.colours = 0b011;
    }
    layout.pictures.push_back(left);
    layout.pictures.push_back(right);
  }
  return layout;
}

bool copy_picture(std::vector<std::uint8_t>& frame, int frame_width, int frame_height,
                  const unsigned char* pixels, int width, int height, int pixel_bytes, std::size_t row_bytes,
                  int x0, std::uint8_t colours) {
  if (x0 < 0 || x0 + width > frame_width || height != frame_height ||
      (pixel_bytes != 3 && pixel_bytes != 4) ||
      frame.size() != static_cast<std::size_t>(frame_width) * frame_height * 3)
    return false;
  const std::size_t row = static_cast<std::size_t>(frame_width) * 3;
  for (int y = 0; y < height; ++y) {  // OpenGL's bottom row first to the window's top row first
    const unsigned char* from = pixels + static_cast<std::size_t>(height - 1 - y) * row_bytes;
    unsigned char* to = &frame[static_cast<std::size_t>(y) * row + static_cast<std::size_t>(x0) * 3];
    if (colours == 0b111 && pixel_bytes == 3) {
      std::copy(from, from + static_cast<std::size_t>(width) * 3, to);
      continue;
    }
    for (int x = 0; x < width; ++x)
      for (int k = 0; k < 3; ++k)
        if (colours & (0b100 >> k)) to[3 * x + k] = from[pixel_bytes * x + k];
  }
  return true;
}

}  // namespace harbour::station
