#pragma once
/// A GLFW window with an OpenGL 3.3 core context, its entry points through libepoxy.
///
/// One thread owns a context: it is made current on the thread that creates it, and every
/// render/ call that touches GL runs there with it current. GLFW is initialised with the
/// first context and terminated with the last. A hidden window still has a default
/// framebuffer of its size, which is what headless runs and the render tests draw into
/// (under `xvfb-run -a`).

#include <string>

#include <glm/vec2.hpp>

struct GLFWwindow;

namespace voxhap::render {

/// How to open the window.
/// Whether the environment names a display (DISPLAY or WAYLAND_DISPLAY) to open windows on.
bool hasDisplay();

struct GlContextOptions {
  int widthPx = 1280;  ///< window size in screen coordinates (= pixels without HiDPI scaling)
  int heightPx = 720;
  std::string title = "Voxhap";
  bool visible = true;  ///< false: a hidden window, for headless runs and tests
  bool vsync = true;    ///< false: swapBuffers does not wait for the display (benchmarks)
};

/// A window and its current GL 3.3 core context. Not copyable, not movable.
class GlContext {
public:
  /// Opens the window and makes its context current. Throws voxhap::Error when there is
  /// no display, GLFW cannot start, or the driver offers no GL 3.3 core context.
  explicit GlContext(const GlContextOptions& options = {});
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  GLFWwindow* window() const { return window_; }
  /// Size of the default framebuffer, px (may differ from the window size on HiDPI).
  glm::ivec2 framebufferSizePx() const;
  void makeCurrent();
  void swapBuffers();
  /// Processes pending window events (input callbacks run here).
  void pollEvents();
  bool shouldClose() const;
  /// GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa".
  std::string rendererDescription() const;

private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace voxhap::render
