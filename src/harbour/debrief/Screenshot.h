#pragma once

#include <optional>
#include <string>
#include <vector>

namespace harbour::debrief {

/// `harboursim screenshot`: the exercise driven by the autopilot to a moment, drawn by the image generator
/// (headless) from a view, written as a PNG.
struct ScreenshotOptions {
  std::string exercise;
  double at_s = 10.0;
  std::string view = "cab";  ///< cab, chase
  int width = 1280, height = 720;
  std::string out;
  std::optional<double> time_of_day_h, visibility_m, rain_mm_per_h,
      cloud_oktas;  ///< instructor settings at the start
  /// the free view's camera: x, y, z [m], yaw and pitch [deg] (yaw from +x towards +y)
  std::vector<double> camera;
  std::vector<std::string> commands;   ///< instructor commands on the way there, AT:KIND[:VALUES] (as `run`)
  std::optional<bool> soft_shadows;    ///< filtered shadow edges (unset: the renderer's default)
  std::optional<bool> surface_detail;  ///< surfaces with detail textures (unset: the renderer's default)
  std::optional<int> multisamples;     ///< anti-aliasing samples per pixel (unset: the renderer's default)
  std::string looks;  ///< a look file to draw with (empty: the shipped data/visuals/harbour.yaml)
};
int take_screenshot(const ScreenshotOptions& options);

}  // namespace harbour::debrief
