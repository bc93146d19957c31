#pragma once

#include <string>

namespace harbour::apps {

/// `harboursim render`: a recording re-simulated and drawn into a debrief video (ffmpeg, H.264 MP4) with the
/// HUD and the evaluation's events as they happened.
struct RenderOptions {
  std::string recording, exercise, out;
  std::string view = "chase";
  int width = 960, height = 540;
  double fps = 25.0;
  double from_s = 0.0, to_s = -1.0;  ///< the span drawn (to: the recording's end)
};
int render_video(const RenderOptions& options);

}  // namespace harbour::apps
