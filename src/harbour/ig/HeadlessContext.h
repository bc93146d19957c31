#pragma once

#include <string>

#include <osgViewer/GraphicsWindow>

namespace harbour::ig {

/// An OpenGL context without a display: EGL on Mesa's surfaceless platform with a pbuffer, made current on
/// the calling thread; OSG renders into it as an embedded window. Works with DISPLAY unset and no GPU
/// (llvmpipe). Throws naming the EGL step that failed.
class HeadlessContext {
 public:
  HeadlessContext(int width, int height);
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  /// The renderer's name (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
  std::string renderer() const;

 private:
  int width_, height_;
  void* display_ = nullptr;
  void* context_ = nullptr;
  void* surface_ = nullptr;
};

}  // namespace harbour::ig
