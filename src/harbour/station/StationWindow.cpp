#include "harbour/station/StationWindow.h"

#include <SDL.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "harbour/station/DisplayLayout.h"

namespace harbour::station {

StationWindow::StationWindow(int width, int height, const std::string& title, bool fullscreen, int output)
    : width_(width), height_(height) {
  if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0)
    throw std::runtime_error(std::string("no window: ") + SDL_GetError());
  const int outputs = SDL_GetNumVideoDisplays();
  const int on = output < outputs ? output : 0;
  // no larger than the display's usable area (its panels left), the picture's shape kept
  int window_width = width, window_height = height;
  SDL_Rect usable{};
  if (SDL_GetDisplayUsableBounds(on, &usable) == 0 && usable.w > 0 && usable.h > 0) {
    const double fit = std::min({1.0, 0.95 * usable.w / width, 0.95 * usable.h / height});
    window_width = std::max(160, static_cast<int>(width * fit));
    window_height = std::max(90, static_cast<int>(height * fit));
  }
  window_ =
      SDL_CreateWindow(title.c_str(), static_cast<int>(SDL_WINDOWPOS_CENTERED_DISPLAY(on)),
                       static_cast<int>(SDL_WINDOWPOS_CENTERED_DISPLAY(on)), window_width, window_height,
                       SDL_WINDOW_SHOWN | SDL_WINDOW_RESIZABLE |
                           (fullscreen && output < outputs ? SDL_WINDOW_FULLSCREEN_DESKTOP : 0));
  if (!window_) throw std::runtime_error(std::string("no window: ") + SDL_GetError());
  renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
  if (!renderer_) throw std::runtime_error(std::string("no window renderer: ") + SDL_GetError());
  // the picture scaled to whatever size the window takes, its shape kept (bars where the window's differs)
  SDL_RenderSetLogicalSize(renderer_, width, height);
  texture_ = SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING, width, height);
  if (!texture_) throw std::runtime_error(std::string("no window texture: ") + SDL_GetError());
  frame_.assign(static_cast<std::size_t>(width) * height * 3, 0);
}

StationWindow::~StationWindow() {
  if (texture_) SDL_DestroyTexture(texture_);
  if (renderer_) SDL_DestroyRenderer(renderer_);
  if (window_) SDL_DestroyWindow(window_);
  SDL_QuitSubSystem(SDL_INIT_VIDEO);
}

void StationWindow::hand_over(const unsigned char* pixels, int width, int height, int pixel_bytes,
                              std::size_t row_bytes, int x0, std::uint8_t colours, bool last) {
  const std::lock_guard lock(mutex_);
  if (copy_picture(frame_, width_, height_, pixels, width, height, pixel_bytes, row_bytes, x0, colours) &&
      last)
    fresh_ = true;
}

WindowInput StationWindow::pump() {
  WindowInput in;
  SDL_Event e;
  bool redraw = false;
  while (SDL_PollEvent(&e)) {
    if (e.type == SDL_QUIT || (e.type == SDL_WINDOWEVENT && e.window.event == SDL_WINDOWEVENT_CLOSE))
      in.open = false;
    if (e.type == SDL_WINDOWEVENT &&
        (e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED || e.window.event == SDL_WINDOWEVENT_EXPOSED))
      redraw = true;
    if (e.type == SDL_KEYDOWN && !e.key.repeat) {
      in.keys_went_down.push_back(e.key.keysym.scancode);
      if (e.key.keysym.scancode == SDL_SCANCODE_F1) in.help_toggled = true;
      if (e.key.keysym.scancode == SDL_SCANCODE_KP_5) in.recentre = true;
      if (e.key.keysym.scancode == SDL_SCANCODE_F11) {
        const bool full = (SDL_GetWindowFlags(window_) & SDL_WINDOW_FULLSCREEN_DESKTOP) != 0;
        SDL_SetWindowFullscreen(window_, full ? 0 : SDL_WINDOW_FULLSCREEN_DESKTOP);
      }
    }
    if (e.type == SDL_MOUSEMOTION && (e.motion.state & SDL_BUTTON_LMASK)) {
      in.drag_right_px += e.motion.xrel;
      in.drag_down_px += e.motion.yrel;
    }
  }
  const Uint8* keys = SDL_GetKeyboardState(nullptr);
  in.look_yaw_keys = (keys[SDL_SCANCODE_KP_4] ? 1 : 0) - (keys[SDL_SCANCODE_KP_6] ? 1 : 0);
  in.look_pitch_keys = (keys[SDL_SCANCODE_KP_8] ? 1 : 0) - (keys[SDL_SCANCODE_KP_2] ? 1 : 0);
  in.dragging = (SDL_GetMouseState(nullptr, nullptr) & SDL_BUTTON_LMASK) != 0;
  {
    const std::lock_guard lock(mutex_);
    if (!fresh_ && !redraw) return in;
    SDL_UpdateTexture(texture_, nullptr, frame_.data(), width_ * 3);
    fresh_ = false;
  }
  SDL_SetRenderDrawColor(renderer_, 0, 0, 0, 255);
  SDL_RenderClear(renderer_);
  SDL_RenderCopy(renderer_, texture_, nullptr, nullptr);
  SDL_RenderPresent(renderer_);
  ++frames_shown_;
  return in;
}

void StationWindow::size(int& width, int& height) const {
  SDL_GetWindowSize(window_, &width, &height);
}

void StationWindow::resize(int width, int height) {
  SDL_SetWindowSize(window_, width, height);
}

void StationWindow::move_mouse(int x, int y) {
  SDL_WarpMouseInWindow(window_, x, y);
}

std::vector<std::uint8_t> StationWindow::shown(int& width, int& height) {
  // the whole window as it shows now, bars included
  SDL_GetRendererOutputSize(renderer_, &width, &height);
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * height * 3);
  SDL_RenderSetLogicalSize(renderer_, 0, 0);  // read in the window's own pixels
  SDL_RenderReadPixels(renderer_, nullptr, SDL_PIXELFORMAT_RGB24, pixels.data(), width * 3);
  SDL_RenderSetLogicalSize(renderer_, width_, height_);
  return pixels;
}

}  // namespace harbour::station
