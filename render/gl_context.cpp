#include "render/gl_context.h"

#include <cstdlib>
#include <mutex>

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "haptics/core/error.h"

namespace voxhap::render {
namespace {

/// GLFW's last error message, kept by its error callback for our exceptions.
std::string& lastGlfwError() {
  static std::string message;
  return message;
}

std::mutex& glfwMutex() {
  static std::mutex m;
  return m;
}
int glfwUsers = 0;  ///< live GlContexts; guarded by glfwMutex

void acquireGlfw() {
  std::lock_guard lock(glfwMutex());
  if (glfwUsers == 0) {
    if (!hasDisplay()) throw Error("no display: run under xvfb-run -a or set DISPLAY");
    glfwSetErrorCallback([](int, const char* message) { lastGlfwError() = message ? message : "unknown"; });
    if (!glfwInit()) throw Error("cannot start GLFW: " + lastGlfwError());
  }
  ++glfwUsers;
}

void releaseGlfw() {
  std::lock_guard lock(glfwMutex());
  if (--glfwUsers == 0) glfwTerminate();
}

}  // namespace

bool hasDisplay() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 && *x11) || (wayland && *wayland);
}

GlContext::GlContext(const GlContextOptions& options) {
  acquireGlfw();
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  glfwWindowHint(GLFW_STENCIL_BITS, 8);
  glfwWindowHint(GLFW_SAMPLES, 0);  // single-sampled: screenshots compare exact pixels
  lastGlfwError().clear();
  window_ = glfwCreateWindow(options.widthPx, options.heightPx, options.title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string why = lastGlfwError();
    releaseGlfw();
    throw Error("cannot open a window with an OpenGL 3.3 core context: " + (why.empty() ? "unknown" : why));
  }
  glfwMakeContextCurrent(window_);
  if (epoxy_gl_version() < 33) {
    const int version = epoxy_gl_version();
    glfwDestroyWindow(window_);
    releaseGlfw();
    throw Error("the GL driver offers OpenGL " + std::to_string(version / 10) + "." +
                std::to_string(version % 10) + ", the renderer needs 3.3 core");
  }
  glfwSwapInterval(options.vsync ? 1 : 0);
}

GlContext::~GlContext() {
  glfwDestroyWindow(window_);
  releaseGlfw();
}

glm::ivec2 GlContext::framebufferSizePx() const {
  glm::ivec2 size{0};
  glfwGetFramebufferSize(window_, &size.x, &size.y);
  return size;
}

void GlContext::makeCurrent() {
  glfwMakeContextCurrent(window_);
}
void GlContext::swapBuffers() {
  glfwSwapBuffers(window_);
}
void GlContext::pollEvents() {
  glfwPollEvents();
}
bool GlContext::shouldClose() const {
  return glfwWindowShouldClose(window_) != 0;
}

std::string GlContext::rendererDescription() const {
  const auto text = [](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "?");
  };
  return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

}  // namespace voxhap::render
