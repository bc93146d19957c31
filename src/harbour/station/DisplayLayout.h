#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "harbour/station/Profile.h"

namespace harbour::station {

/// Where the image generator's pictures go on a station: the windows, and for each picture (each display
/// channel, each eye in stereo) its window, its place there and the colours it gives.
struct DisplayLayout {
  struct Window {
    int width = 0, height = 0;
    int display = 0;  ///< the profile's display it stands for (its name, its full-screen setting)
  };
  struct Picture {
    int channel = 0;               ///< the profile's display channel it shows
    double eye_offset_m = 0.0;     ///< stereo: along the view's right axis (0: no stereo)
    double pixel_aspect = 1.0;     ///< 2 for a side-by-side half
    int window = 0, x0 = 0;        ///< its tile: the window, the tile's left column
    std::uint8_t colours = 0b111;  ///< red, green, blue bits: which colours it writes (anaglyph: red or cyan)
  };
  int render_width = 0, render_height = 0;  ///< every picture's size
  std::vector<Window> windows;
  std::vector<Picture> pictures;  ///< in drawing order
};

/// The layout of a profile's displays: the channels side by side in one window or a window each, at most
/// `max_width` pixels drawn across all channels (a software renderer's budget; each keeps its aspect ratio),
/// stereo as two pictures per channel (half-width halves side by side, or a red and a cyan one over each
/// other). No windows or pictures for a profile without displays.
DisplayLayout layout_displays(const Profile& profile, int max_width = 1920);

/// Copies a picture (RGB or RGBA, `pixel_bytes` 3 or 4, rows `row_bytes` apart, bottom row first as OpenGL
/// reads them) into a window's frame (RGB, top row first, `frame_width` across) at column `x0`, writing only
/// the colours `colours` names. False (nothing written) where it does not fit.
bool copy_picture(std::vector<std::uint8_t>& frame, int frame_width, int frame_height,
                  const unsigned char* pixels, int width, int height, int pixel_bytes, std::size_t row_bytes,
                  int x0, std::uint8_t colours);

}  // namespace harbour::station
