#include "StationWindow.h"

#include <SDL.h>

#include <cstring>
#include <stdexcept>

#include "harbour/station/DisplayLayout.h"

namespace harbour::apps {

StationWindow::StationWindow(int width, int height, const std::string& title, bool fullscreen, int output)
    : width_(width), height_(height) {
  if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0)
    throw std::runtime_error(std::string("no window: ") + SDL_GetError());
  const int outputs = SDL_GetNumVideoDisplays();
  const int on = output < outputs ? output : 0;
  window_ = SDL_CreateWindow(
      title.c_str(), static_cast<int>(SDL_WINDOWPOS_CENTERED_DISPLAY(on)),
      static_cast<int>(SDL_WINDOWPOS_CENTERED_DISPLAY(on)), width, height,
      SDL_WINDOW_SHOWN | (fullscreen && output < outputs ? SDL_WINDOW_FULLSCREEN_DESKTOP : 0));
  if (!window_) throw std::runtime_error(std::string("no window: ") + SDL_GetError());
  renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
  if (!renderer_) throw std::runtime_error(std::string("no window renderer: ") + SDL_GetError());
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
  if (station::copy_picture(frame_, width_, height_, pixels, width, height, pixel_bytes, row_bytes, x0,
                            colours) &&
      last)
    fresh_ = true;
}

bool StationWindow::pump() {
  SDL_Event e;
  bool open = true;
  while (SDL_PollEvent(&e))
    if (e.type == SDL_QUIT || (e.type == SDL_WINDOWEVENT && e.window.event == SDL_WINDOWEVENT_CLOSE))
      open = false;
  {
    const std::lock_guard lock(mutex_);
    if (!fresh_) return open;
    SDL_UpdateTexture(texture_, nullptr, frame_.data(), width_ * 3);
    fresh_ = false;
  }
  SDL_RenderClear(renderer_);
  SDL_RenderCopy(renderer_, texture_, nullptr, nullptr);
  SDL_RenderPresent(renderer_);
  ++frames_shown_;
  return open;
}

std::vector<std::uint8_t> StationWindow::shown(int& width, int& height) {
  width = width_;
  height = height_;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width_) * height_ * 3);
  SDL_RenderReadPixels(renderer_, nullptr, SDL_PIXELFORMAT_RGB24, pixels.data(), width_ * 3);
  return pixels;
}

}  // namespace harbour::apps
