// Frame rate of the renderer on the landing gear (≈ 2.7 M static triangles) at 1280×720,
// with and without the static cache (FlyThru, paper §7): each frame moves the actuator a
// little and waits for the GL to finish (glFinish), as a frame on screen would. Run by
// hand under a display: xvfb-run -a build/release/tests/voxhap_render_bench.
// Counter: frames per second. Timings never decide a test.
#include <cmath>
#include <memory>

#include <benchmark/benchmark.h>
#include <epoxy/gl.h>

#include "haptics/scene/builtin/builtin_scenes.h"
#include "render/gl_context.h"
#include "render/orbit_camera.h"
#include "render/scene_renderer.h"

namespace voxhap {
namespace {

constexpr glm::ivec2 kViewportPx{1280, 720};

struct LandingGearView {
  render::GlContext context{
      render::GlContextOptions{kViewportPx.x, kViewportPx.y, "render bench", false, false}};
  Scene scene = makeLandingGear(1);
  std::unique_ptr<render::SceneRenderer> renderer;
  render::OrbitCamera camera;
  LandingGearView() {
    renderer = std::make_unique<render::SceneRenderer>(scene, std::vector<std::string>{"actuator"});
    camera.frame(renderer->sceneBounds(), double(kViewportPx.x) / kViewportPx.y);
  }
};

LandingGearView& view() {
  static LandingGearView v;
  return v;
}

void frames(benchmark::State& state, bool useStaticCache) {
  LandingGearView& v = view();
  std::uint64_t frame = 0;
  for (auto _ : state) {
    const double t = 0.01 * static_cast<double>(frame++);
    v.renderer->setPose(0, Pose{glm::dvec3(0.0, 0.0, 0.005 * std::sin(t)), identityQuat()});
    v.renderer->draw(v.camera, kViewportPx, useStaticCache);
    glFinish();
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_LandingGearFrameFullRedraw(benchmark::State& state) {
  frames(state, false);
}
void BM_LandingGearFrameStaticCache(benchmark::State& state) {
  frames(state, true);
}
BENCHMARK(BM_LandingGearFrameFullRedraw)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_LandingGearFrameStaticCache)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

}  // namespace
}  // namespace voxhap
