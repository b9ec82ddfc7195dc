#include "app/session_shots.h"

#include "render/gl_context.h"
#include "render/orbit_camera.h"
#include "render/scene_renderer.h"
#include "render/screenshot.h"

namespace voxhap::cli {

void writeSessionShots(const Scene& scene, std::span<const std::string> moving, const Bounds& focusWorld,
                       std::span<const SessionShot> shots, const glm::ivec2& sizePx) {
  render::GlContextOptions options;
  options.widthPx = sizePx.x;
  options.heightPx = sizePx.y;
  options.title = "voxhap demo";
  options.visible = false;
  options.vsync = false;
  render::GlContext window(options);
  render::SceneRenderer renderer(scene, moving);
  render::OrbitCamera camera;
  camera.frame(focusWorld, static_cast<double>(sizePx.x) / sizePx.y);
  camera.setSceneBounds(renderer.sceneBounds());  // near and far around the whole gear
  const glm::ivec2 fb = window.framebufferSizePx();
  for (const SessionShot& shot : shots) {
    for (std::size_t i = 0; i < moving.size() && i < shot.poses.size(); ++i) {
      renderer.setPose(i, shot.poses[i]);
      renderer.setOtherInstance(i, i < shot.otherInstances.size() ? shot.otherInstances[i] : std::nullopt);
    }
    renderer.draw(camera, fb, true);
    render::saveScreenshot(shot.file, fb);
    window.swapBuffers();
  }
}

Bounds boundsAt(const SceneObject& object, const Pose& pose) {
  const Bounds b = object.bounds();
  Bounds out;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                       (corner & 4) ? b.max.z : b.min.z);
    out.add(apply(pose, p));
  }
  return out;
}

}  // namespace voxhap::cli
