#include "render/screenshot.h"

#include <cstring>

#include <epoxy/gl.h>

#include "haptics/core/error.h"
#include "render/gl_check.h"

namespace voxhap::render {

RgbImage readFramebuffer(const glm::ivec2& sizePx) {
  if (sizePx.x <= 0 || sizePx.y <= 0) throw Error("screenshot: empty framebuffer");
  RgbImage image(sizePx.x, sizePx.y, 0, 0, 0);
  std::vector<std::uint8_t> bottomUp(image.rgb.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, sizePx.x, sizePx.y, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
  throwOnGlError("screenshot: reading the framebuffer");
  const std::size_t rowBytes = static_cast<std::size_t>(sizePx.x) * 3;
  for (std::size_t y = 0; y < static_cast<std::size_t>(sizePx.y); ++y) {
    std::memcpy(&image.rgb[y * rowBytes], &bottomUp[(static_cast<std::size_t>(sizePx.y) - 1 - y) * rowBytes],
                rowBytes);
  }
  return image;
}

void saveScreenshot(const std::filesystem::path& file, const glm::ivec2& sizePx) {
  writePng(file, readFramebuffer(sizePx));
}

}  // namespace voxhap::render
