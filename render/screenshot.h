#pragma once
/// Screenshots: the default framebuffer read back into an image (rows top to bottom).

#include <filesystem>

#include <glm/vec2.hpp>

#include "render/png_image.h"

namespace voxhap::render {

/// Reads the default framebuffer's back buffer (what the last draw made, before the
/// swap) over `sizePx` from the bottom-left corner; rows are flipped so that row 0 is
/// the top of the window. Needs a current context.
RgbImage readFramebuffer(const glm::ivec2& sizePx);

/// readFramebuffer then writePng; throws voxhap::Error naming the file.
void saveScreenshot(const std::filesystem::path& file, const glm::ivec2& sizePx);

}  // namespace voxhap::render
