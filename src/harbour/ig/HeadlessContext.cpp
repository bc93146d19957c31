#include "harbour/ig/HeadlessContext.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>

#include <stdexcept>

namespace harbour::ig {

namespace {
[[noreturn]] void fail(const char* step) {
  throw std::runtime_error(std::string("headless OpenGL (EGL): ") + step + " failed (EGL error 0x" + [] {
    char hex[16];
    std::snprintf(hex, sizeof hex, "%x", static_cast<unsigned>(eglGetError()));
    return std::string(hex);
  }() + ")");
}
}  // namespace

HeadlessContext::HeadlessContext(int width, int height) : width_(width), height_(height) {
  const auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDisplay display = get_platform_display
                           ? get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)
                           : eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (display == EGL_NO_DISPLAY) fail("eglGetPlatformDisplayEXT(surfaceless)");
  if (!eglInitialize(display, nullptr, nullptr)) fail("eglInitialize");
  display_ = display;
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE,
                                      EGL_PBUFFER_BIT,
                                      EGL_RED_SIZE,
                                      8,
                                      EGL_GREEN_SIZE,
                                      8,
                                      EGL_BLUE_SIZE,
                                      8,
                                      EGL_ALPHA_SIZE,
                                      8,
                                      EGL_DEPTH_SIZE,
                                      24,
                                      EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT,
                                      EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, config_attributes, &config, 1, &configs) || configs < 1)
    fail("eglChooseConfig");
  const EGLint pbuffer_attributes[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
  surface_ = eglCreatePbufferSurface(display, config, pbuffer_attributes);
  if (surface_ == EGL_NO_SURFACE) fail("eglCreatePbufferSurface");
  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(OpenGL)");
  context_ = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (context_ == EGL_NO_CONTEXT) fail("eglCreateContext");
  if (!eglMakeCurrent(display, surface_, surface_, context_)) fail("eglMakeCurrent");
}

HeadlessContext::~HeadlessContext() {
  if (!display_) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_) eglDestroyContext(display_, context_);
  if (surface_) eglDestroySurface(display_, surface_);
  eglTerminate(display_);
}

std::string HeadlessContext::renderer() const {
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return name ? name : "?";
}

}  // namespace harbour::ig
