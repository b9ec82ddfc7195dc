#include "render/gl_check.h"

#include <cstdio>
#include <string>

#include <epoxy/gl.h>

#include "haptics/core/error.h"

namespace voxhap::render {
namespace {

const char* errorName(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "unknown";
  }
}

}  // namespace

void throwOnGlError(const char* what) {
  const GLenum first = glGetError();
  if (first == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", first);
  throw Error(std::string(what) + ": GL error " + code + " (" + errorName(first) + ")");
}

}  // namespace voxhap::render
