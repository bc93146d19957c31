#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

struct SDL_Window;
struct SDL_Renderer;
struct SDL_Texture;

namespace harbour::apps {

/// The trainee's window: shows the image generator's newest frame (handed over from its render thread) and
/// gives SDL the keyboard and mouse focus the keyboard-and-mouse mapping reads. Events are pumped on the
/// thread that made it.
class StationWindow {
 public:
  /// Opens the window (throws naming SDL's error when there is no display), full screen on the display
  /// system's output `output` when asked and that output exists (else a window on the first).
  StationWindow(int width, int height, const std::string& title, bool fullscreen = false, int output = 0);
  ~StationWindow();
  StationWindow(const StationWindow&) = delete;
  StationWindow& operator=(const StationWindow&) = delete;

  /// Render thread: a picture of RGB or RGBA pixels (`pixel_bytes` 3 or 4), rows `row_bytes` apart, bottom
  /// row first (as OpenGL reads them), into its tile from column `x0`, writing the colours `colours` names
  /// (station::copy_picture); shown once the `last` picture of a frame is in (not an eye of one frame beside
  /// the other eye of the previous).
  void hand_over(const unsigned char* pixels, int width, int height, int pixel_bytes, std::size_t row_bytes,
                 int x0 = 0, std::uint8_t colours = 0b111, bool last = true);
  /// Window thread: events, then the newest frame if there is one; false once the window is closed.
  bool pump();
  /// What the window shows now (RGB, top row first): for tests.
  std::vector<std::uint8_t> shown(int& width, int& height);
  long frames_shown() const { return frames_shown_; }

 private:
  SDL_Window* window_ = nullptr;
  SDL_Renderer* renderer_ = nullptr;
  SDL_Texture* texture_ = nullptr;
  int width_, height_;
  std::mutex mutex_;
  std::vector<std::uint8_t> frame_;  // top row first
  bool fresh_ = false;
  long frames_shown_ = 0;
};

}  // namespace harbour::apps
