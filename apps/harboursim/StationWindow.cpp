#include "StationWindow.h"

#include <SDL.h>

#include <cstring>
#include <stdexcept>

namespace harbour::apps {

StationWindow::StationWindow(int width, int height, const std::string& title)
    : width_(width), height_(height) {
  if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0)
    throw std::runtime_error(std::string("no window: ") + SDL_GetError());
  window_ = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width, height,
                             SDL_WINDOW_SHOWN);
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
                              std::size_t row_bytes, int channel, int channels) {
  if (width * channels != width_ || height != height_ || (pixel_bytes != 3 && pixel_bytes != 4)) return;
  const std::size_t row = static_cast<std::size_t>(width_) * 3, tile = static_cast<std::size_t>(width) * 3;
  const std::lock_guard lock(mutex_);
  for (int y = 0; y < height; ++y) {  // OpenGL's bottom row first to the window's top row first
    const unsigned char* from = pixels + static_cast<std::size_t>(height - 1 - y) * row_bytes;
    unsigned char* to = &frame_[static_cast<std::size_t>(y) * row + static_cast<std::size_t>(channel) * tile];
    if (pixel_bytes == 3) {
      std::memcpy(to, from, tile);
    } else {
      for (int x = 0; x < width; ++x)
        std::memcpy(to + 3 * x, from + 4 * x, 3);
    }
  }
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
