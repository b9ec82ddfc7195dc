#pragma once
/// Test support for render tests: one hidden GL window shared by the whole test binary
/// (run under `xvfb-run -a`), small scenes with known colours and positions, and pixel
/// classifiers that say what a screenshot must show there.

#include <array>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/scene.h"
#include "render/gl_context.h"
#include "render/orbit_camera.h"
#include "render/png_image.h"

namespace voxhap::test {

/// Size of the shared window's framebuffer, px.
inline constexpr glm::ivec2 kViewportPx{320, 240};

/// The shared hidden window, opened by the first test that needs GL.
inline render::GlContext& glTestContext() {
  static render::GlContext context(render::GlContextOptions{kViewportPx.x, kViewportPx.y,
                                                            "voxhap render tests",
                                                            /*visible=*/false, /*vsync=*/false});
  context.makeCurrent();
  return context;
}

inline constexpr glm::vec4 kWallColour{0.8f, 0.05f, 0.05f, 1.0f};
inline constexpr glm::vec4 kSliderColour{0.05f, 0.1f, 0.9f, 1.0f};
inline constexpr glm::vec4 kCapColour{0.05f, 0.8f, 0.1f, 1.0f};
inline constexpr glm::dvec3 kWallCentre{0.0, 0.0, 0.0};
inline constexpr double kWallHalfM = 0.05;
/// The slider's body centre at the scene placement (identity pose).
inline constexpr glm::dvec3 kSliderCentre{0.12, 0.0, 0.0};
inline constexpr double kSliderHalfM = 0.02;

/// A static red cube "wall" (10 cm, centred on the origin) and a moving object "slider":
/// a blue 4 cm cube at (12, 0, 0) cm (part 0) with a green 2 cm cap on top (part 1).
inline Scene wallAndSlider() {
  Scene scene;
  scene.sourceName = "wall and slider";
  SceneObject wall;
  wall.name = "wall";
  TriangleMesh wallMesh;
  appendBox(wallMesh, glm::translate(glm::dmat4(1.0), kWallCentre), glm::dvec3(kWallHalfM));
  wall.parts.push_back(makePart("wall", kWallColour, std::move(wallMesh)));
  scene.objects.push_back(std::move(wall));
  SceneObject slider;
  slider.name = "slider";
  slider.settings.role = ObjectRole::Dynamic;
  TriangleMesh body;
  appendBox(body, glm::translate(glm::dmat4(1.0), kSliderCentre), glm::dvec3(kSliderHalfM));
  slider.parts.push_back(makePart("slider body", kSliderColour, std::move(body)));
  TriangleMesh cap;
  appendBox(cap, glm::translate(glm::dmat4(1.0), kSliderCentre + glm::dvec3(0.0, 0.0, 0.03)),
            glm::dvec3(0.01));
  slider.parts.push_back(makePart("slider cap", kCapColour, std::move(cap)));
  scene.objects.push_back(std::move(slider));
  return scene;
}

/// A camera on the (+x, -y) side of the wall, a little above, framing `bounds`.
inline render::OrbitCamera cameraFraming(const Bounds& bounds) {
  render::OrbitCamera camera;
  camera.setAngles(-0.5, 0.3);
  camera.frame(bounds, static_cast<double>(kViewportPx.x) / kViewportPx.y);
  return camera;
}

using Pixel = std::array<std::uint8_t, 3>;

/// The pixel where `pointWorld` projects.
inline Pixel pixelAt(const render::RgbImage& image, const render::OrbitCamera& camera,
                     const glm::dvec3& pointWorld) {
  const render::ScreenPoint s = camera.project(pointWorld, kViewportPx);
  return image.at(static_cast<int>(s.pixelPx.x), static_cast<int>(s.pixelPx.y));
}

inline std::string describe(const Pixel& p) {
  return "(" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + ")";
}

/// Red dominates: the wall, lit.
inline bool reddish(const Pixel& p) {
  return p[0] > 90 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
}
/// Blue dominates: the slider's body, lit.
inline bool bluish(const Pixel& p) {
  return p[2] > 90 && p[2] > 2 * p[0] && 2 * p[2] > 3 * p[1];
}
/// Green dominates: the force arrow or the slider's cap.
inline bool greenish(const Pixel& p) {
  return p[1] > 90 && 2 * p[1] > 3 * p[0] && 2 * p[1] > 3 * p[2];
}
/// The proximity ramp's red end: touching.
inline bool warmRed(const Pixel& p) {
  return p[0] > 150 && p[1] < 60 && p[2] < 60;
}

/// Writes `image` to $VOXHAP_RENDER_TEST_PNG_DIR/`name`.png when that variable is set, for
/// looking at what a test saw; does nothing otherwise.
inline void keepScreenshot(const render::RgbImage& image, const std::string& name) {
  const char* dir = std::getenv("VOXHAP_RENDER_TEST_PNG_DIR");
  if (dir && *dir) render::writePng(std::string(dir) + "/" + name + ".png", image);
}

/// Largest per-channel difference between two images of the same size, and how many
/// pixels differ by more than `tolerance` in some channel.
struct ImageDifference {
  int maxChannelDifference = 0;
  std::size_t pixelsOverTolerance = 0;
};
inline ImageDifference compareImages(const render::RgbImage& a, const render::RgbImage& b, int tolerance) {
  ImageDifference d;
  for (std::size_t i = 0; i < a.rgb.size(); i += 3) {
    int worst = 0;
    for (std::size_t c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(a.rgb[i + c]) - int(b.rgb[i + c])));
    d.maxChannelDifference = std::max(d.maxChannelDifference, worst);
    if (worst > tolerance) ++d.pixelsOverTolerance;
  }
  return d;
}

}  // namespace voxhap::test
