#include "render/gl_context.h"

#include <cstdio>
#include <cstdlib>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "render/screenshot.h"
#include "tests/render/render_test_support.h"

namespace voxhap::render {
namespace {

TEST(GlContext, OpensAHiddenCoreContextOfTheRequestedSize) {
  GlContext& context = test::glTestContext();
  EXPECT_EQ(context.framebufferSizePx(), test::kViewportPx);
  EXPECT_GE(epoxy_gl_version(), 33);
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_FALSE(context.rendererDescription().empty());
  std::printf("renderer: %s\n", context.rendererDescription().c_str());
}

TEST(GlContext, WithoutADisplaySaysHowToGetOne) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // re-runs the binary: no GL in the child yet
  EXPECT_EXIT(
      {
        unsetenv("DISPLAY");
        unsetenv("WAYLAND_DISPLAY");
        try {
          GlContext context(GlContextOptions{64, 64, "no display", false, false});
        } catch (const Error& e) {
          std::fprintf(stderr, "%s\n", e.what());
          std::_Exit(3);
        }
        std::_Exit(0);
      },
      testing::ExitedWithCode(3), "no display: run under xvfb-run -a or set DISPLAY");
}

TEST(Screenshot, RowZeroIsTheTopOfTheWindow) {
  test::glTestContext();
  const glm::ivec2 size = test::kViewportPx;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, size.x, size.y);
  glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  // GL's window origin is the bottom-left: paint the top quarter red
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, size.y - size.y / 4, size.x, size.y / 4);
  glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  const RgbImage image = readFramebuffer(size);
  ASSERT_EQ(image.width, size.x);
  ASSERT_EQ(image.height, size.y);
  EXPECT_EQ(image.at(5, 2), (std::array<std::uint8_t, 3>{255, 0, 0}));
  EXPECT_EQ(image.at(5, size.y - 3), (std::array<std::uint8_t, 3>{0, 0, 255}));
}

}  // namespace
}  // namespace voxhap::render
