// Point-test throughput (issue 3): the ball's pointshell sampled against the socket's
// voxmap, as in the paper's ball-and-socket benchmark, each iteration at a different
// rotation of the ball about its centre so that successive passes touch different voxels.
// The socket's voxmap at 0.15 mm (tens of MB) does not fit the caches, so lookups are
// cache-cold as in a real scene; points are visited in pointshell order (chunk by chunk),
// as the haptic frame visits them. Counters: points tested per second, contacts per pass.
#include <cmath>
#include <map>
#include <memory>

#include <benchmark/benchmark.h>
#include <glm/gtc/quaternion.hpp>

#include "haptics/collide/point_sampler.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/sim/scene_model.h"

namespace voxhap {
namespace {

struct BallInSocket {
  Voxmap socket;
  Pointshell ball;
  std::vector<PointContact> contacts;
};

const BallInSocket& ballInSocket(double voxelM) {
  static std::map<double, std::unique_ptr<BallInSocket>> cache;
  auto& entry = cache[voxelM];
  if (!entry) {
    const Scene scene = makeBallAndSocket();
    entry = std::make_unique<BallInSocket>();
    VoxelizeOptions voxels;
    voxels.voxelSizeM = voxelM;
    const SceneObject* socket[] = {scene.find("socket")};
    entry->socket = voxelizeObjects(socket, voxels, {});
    PointshellOptions points;
    points.pointSpacingM = voxelM;
    points.displacementM = -0.5 * voxelM;
    entry->ball = pointshellOf(*scene.find("ball"), points, {});
    entry->contacts.resize(entry->ball.size());
  }
  return *entry;
}

void pointTests(benchmark::State& state) {
  const double voxelM = static_cast<double>(state.range(0)) * 1e-5;
  const BallInSocket& b = ballInSocket(voxelM);
  auto& contacts = const_cast<std::vector<PointContact>&>(b.contacts);
  const auto shifts = fieldShiftsByFeature(true, b.socket.encoding());
  const auto points = static_cast<std::uint32_t>(b.ball.size());
  double angle = 0.0;
  std::uint64_t found = 0;
  for (auto _ : state) {
    angle += 0.37;
    const Pose pose{glm::dvec3(0.0), glm::angleAxis(angle, glm::normalize(glm::dvec3(1.0, 0.3, 0.2)))};
    const VoxelTransform transform = VoxelTransform::make(pose, b.socket.grid());
    found +=
        samplePoints(b.ball, b.socket, transform, shifts, kDefaultForceLayer, 0, points, contacts.data());
    benchmark::ClobberMemory();
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["contacts_per_pass"] = static_cast<double>(found) / static_cast<double>(state.iterations());
  state.counters["voxmap_MB"] = static_cast<double>(b.socket.memoryBytes()) / 1e6;
  state.counters["tests_per_s"] =
      benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsIterationInvariantRate);
}
// voxel size in units of 10 µm: 0.35 mm and 0.15 mm
BENCHMARK(pointTests)->Arg(35)->Arg(15)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace voxhap

BENCHMARK_MAIN();
