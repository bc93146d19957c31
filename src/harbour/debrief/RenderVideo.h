#pragma once

#include <string>

namespace harbour::debrief {

/// `harboursim render`: a recording re-simulated and drawn into a debrief video (ffmpeg, H.264 MP4) with the
/// HUD, the evaluation's events as they happened and the cab's sound (AAC), and/or its sound alone (WAV).
struct RenderOptions {
  std::string recording, exercise, out;
  std::string audio;        ///< WAV file of the sound track (16-bit, 48 kHz)
  bool sound = true;        ///< the video carries the sound track
  bool headphones = false;  ///< the sound through the HRTF (for headphones) rather than for two speakers
  std::string view = "chase";
  int width = 960, height = 540;
  double fps = 25.0;
  double from_s = 0.0, to_s = -1.0;  ///< the span drawn (to: the recording's end)
};
int render_video(const RenderOptions& options);

}  // namespace harbour::debrief
