#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

struct SDL_Window;
struct SDL_Renderer;
struct SDL_Texture;

namespace harbour::station {

/// What the trainee did at the window since the last pump, beyond the machine's controls: the station's own
/// keys (F1 the key list, the keypad looking round, keypad 5 back to the line of sight) and a mouse drag with
/// its left button held (looking round).
struct WindowInput {
  bool open = true;
  bool help_toggled = false;
  int look_yaw_keys = 0, look_pitch_keys = 0;  ///< keypad 4/6 (+1 left), 8/2 (+1 up) held
  bool recentre = false;                       ///< keypad 5
  bool dragging = false;                       ///< the left button held
  double drag_right_px = 0.0, drag_down_px = 0.0;
  std::vector<int> keys_went_down;  ///< SDL scancodes pressed since the last pump (not repeats)
};

/// The trainee's window: shows the image generator's newest frame (handed over from its render thread),
/// scaled to the window as it is resized (F11 full screen and back), and gives SDL the keyboard focus the
/// keyboard mappings read. It opens no larger than the display it is on, keeping the picture's shape. Events
/// are pumped on the thread that made it.
class StationWindow {
 public:
  /// Opens the window (throws naming SDL's error when there is no display), full screen on the display
  /// system's output `output` when asked and that output exists (else a window on the first). The picture
  /// stays `width` x `height`; the window fits the display.
  StationWindow(int width, int height, const std::string& title, bool fullscreen = false, int output = 0);
  ~StationWindow();
  StationWindow(const StationWindow&) = delete;
  StationWindow& operator=(const StationWindow&) = delete;

  /// Render thread: a picture of RGB or RGBA pixels (`pixel_bytes` 3 or 4), rows `row_bytes` apart, bottom
  /// row first (as OpenGL reads them), into its tile from column `x0`, writing the colours `colours` names
  /// (copy_picture); shown once the `last` picture of a frame is in (not an eye of one frame beside
  /// the other eye of the previous).
  void hand_over(const unsigned char* pixels, int width, int height, int pixel_bytes, std::size_t row_bytes,
                 int x0 = 0, std::uint8_t colours = 0b111, bool last = true);
  /// Window thread: events, then the newest frame if there is one; `open` false once the window is closed.
  WindowInput pump();
  /// The window's size now [pixels] (it may be resized).
  void size(int& width, int& height) const;
  /// Resizes it as a window manager would (tests).
  void resize(int width, int height);
  /// Puts the mouse pointer at a point of the window (tests).
  void move_mouse(int x, int y);
  /// What the window shows now (RGB, top row first): for tests.
  std::vector<std::uint8_t> shown(int& width, int& height);
  long frames_shown() const { return frames_shown_; }

 private:
  SDL_Window* window_ = nullptr;
  SDL_Renderer* renderer_ = nullptr;
  SDL_Texture* texture_ = nullptr;
  int width_, height_;  // the picture's
  std::mutex mutex_;
  std::vector<std::uint8_t> frame_;  // top row first
  bool fresh_ = false;
  long frames_shown_ = 0;
};

}  // namespace harbour::station
