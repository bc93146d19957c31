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
  /// Opens the window (throws naming SDL's error when there is no display).
  StationWindow(int width, int height, const std::string& title);
  ~StationWindow();
  StationWindow(const StationWindow&) = delete;
  StationWindow& operator=(const StationWindow&) = delete;

  /// Render thread: a frame of RGB or RGBA pixels (`pixel_bytes` 3 or 4), rows `row_bytes` apart, bottom row
  /// first (as OpenGL reads them).
  /// Channel `channel` of `channels` fills its tile (the window split side by side).
  void hand_over(const unsigned char* pixels, int width, int height, int pixel_bytes, std::size_t row_bytes,
                 int channel = 0, int channels = 1);
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
