#include "render/static_cache.h"

#include <string>

#include <epoxy/gl.h>

#include "haptics/core/error.h"
#include "render/gl_check.h"
#include "render/shaders.h"

namespace voxhap::render {

struct StaticCache::Programs {
  CacheCopyShader copy;
};

StaticCache::StaticCache() : programs_(std::make_unique<Programs>()) {
  glGenVertexArrays(1, &emptyVao_);
  glGenFramebuffers(1, &framebuffer_);
}

StaticCache::~StaticCache() {
  glDeleteFramebuffers(1, &framebuffer_);
  const GLuint textures[] = {colourTexture_, depthTexture_};
  glDeleteTextures(2, textures);
  glDeleteVertexArrays(1, &emptyVao_);
}

void StaticCache::resize(const glm::ivec2& sizePx) {
  const GLuint old[] = {colourTexture_, depthTexture_};
  glDeleteTextures(2, old);
  const auto makeTexture = [&](GLint internalFormat, GLenum format, GLenum type) {
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, internalFormat, sizePx.x, sizePx.y, 0, format, type, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
  };
  colourTexture_ = makeTexture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE);
  depthTexture_ = makeTexture(GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT);
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colourTexture_, 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depthTexture_, 0);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw Error("static cache: the offscreen framebuffer of " + std::to_string(sizePx.x) + "x" +
                std::to_string(sizePx.y) + " px is incomplete (status " + std::to_string(status) + ")");
  }
  throwOnGlError("static cache: creating the offscreen framebuffer");
  sizePx_ = sizePx;
}

bool StaticCache::update(const StaticCacheKey& key, const glm::vec3& clearDisplay,
                         const std::function<void()>& drawStatic) {
  if (valid_ && key == key_) {
    ++stats_.reuses;
    return false;
  }
  if (key.sizePx != sizePx_) resize(key.sizePx);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, key.sizePx.x, key.sizePx.y);
  glClearColor(clearDisplay.r, clearDisplay.g, clearDisplay.b, 1.0f);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  drawStatic();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  key_ = key;
  valid_ = true;
  ++stats_.redraws;
  return true;
}

void StaticCache::copyToFramebuffer() const {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  programs_->copy.program.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, colourTexture_);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, depthTexture_);
  glUniform1i(programs_->copy.colourTexture, 0);
  glUniform1i(programs_->copy.depthTexture, 1);
  glBindVertexArray(emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glDepthFunc(GL_LESS);
}

}  // namespace voxhap::render
