#pragma once
/// GL error checks for set-up code (uploads, framebuffer creation): not for per-frame use.

namespace voxhap::render {

/// Throws voxhap::Error "`what`: GL error 0x0505 (GL_OUT_OF_MEMORY)" when the GL error
/// flag is set; clears every pending error. Needs a current context.
void throwOnGlError(const char* what);

}  // namespace voxhap::render
