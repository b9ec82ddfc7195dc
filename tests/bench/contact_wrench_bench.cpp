// Contact-wrench throughput (issue 13): the tangent-plane forces of the ball's contacts in
// its socket, as the rotation benchmark's frames sum them: the ball seated as `voxhap bench
// rotation` seats it (seated_ball_model.h; the paper's contact: each push along the voxmap
// field's fall direction), the contacts of one pass of point tests at a pose turned about
// the ball's centre, summed by tangentPlaneWrench. Each iteration takes the next of a few
// poses, sampled beforehand, so that the voxmap reads are not all cache-warm. Counters:
// contacts per second, how many of them push. The second argument 1: a frame helper (a
// second thread, frame_helper.h) sums half of them. surfaceContactWrenches: the same with
// contact finer than a voxel, the commands' default (ballInSocketModel: every
// contact pushes, each measured by its voxel's surface plane and its neighbours').
#include <map>
#include <memory>
#include <utility>

#include <benchmark/benchmark.h>
#include <glm/gtc/quaternion.hpp>

#include "haptics/collide/tangent_plane_force.h"
#include "haptics/runtime/frame_helper.h"
#include "tests/bench/seated_ball_model.h"

namespace voxhap {
namespace {

struct SampledPose {
  BodyMotion ball;
  std::vector<PointContact> contacts;
};

struct SeatedBall {
  const SimModel& model;
  std::vector<SampledPose> poses;
};

const SeatedBall& seatedBall(double voxelM, bool surfaceContact) {
  static std::map<std::pair<double, bool>, std::unique_ptr<SeatedBall>> cache;
  auto& entry = cache[{voxelM, surfaceContact}];
  if (entry) return *entry;
  entry = std::make_unique<SeatedBall>(SeatedBall{ballInSocketModel(voxelM, surfaceContact), {}});
  const SimModel& model = entry->model;
  const PairModel& pair = model.pairs[0];
  const MovingObjectModel& ball = model.objects[0];
  const Voxmap& socket = model.voxmapOf(pair);
  constexpr int kPoses = 8;
  for (int i = 0; i < kPoses; ++i) {
    // turned about the ball's centre, which stays where the scene puts it
    const glm::dquat turn = glm::angleAxis(0.37 * (i + 1), glm::normalize(glm::dvec3(1.0, 0.3, 0.2)));
    SampledPose p;
    p.ball.poseWorld = Pose{ball.body.comLocal - turn * ball.body.comLocal, turn};
    p.ball.comLocal = ball.body.comLocal;
    p.ball.angularVelocityWorld = glm::dvec3(0.5, 0.0, 0.0);
    p.contacts.resize(ball.shell.size());
    const VoxelTransform transform = VoxelTransform::make(p.ball.poseWorld, socket.grid());
    const std::uint8_t layer = pair.params.sampledLayer(socket.encoding().maxValue());
    p.contacts.resize(samplePoints(ball.shell, socket, transform, pair.fieldShifts, layer, 0,
                                   static_cast<std::uint32_t>(ball.shell.size()), p.contacts.data()));
    entry->poses.push_back(std::move(p));
  }
  return *entry;
}

void wrenchesOf(benchmark::State& state, bool surfaceContact) {
  const SeatedBall& b = seatedBall(static_cast<double>(state.range(0)) * 1e-5, surfaceContact);
  const PairModel& pair = b.model.pairs[0];
  const Pointshell& shell = b.model.objects[0].shell;
  const Voxmap& socket = b.model.voxmapOf(pair);
  const auto helper = state.range(1) ? std::make_unique<FrameHelper>() : nullptr;
  std::size_t next = 0;
  double contacts = 0.0;
  double pushing = 0.0;
  for (auto _ : state) {
    const SampledPose& p = b.poses[next];
    next = (next + 1) % b.poses.size();
    const PairWrench w = tangentPlaneWrench(shell, socket, pair.params, p.ball, BodyMotion{}, p.contacts,
                                            nullptr, helper.get());
    benchmark::DoNotOptimize(w);
    contacts += static_cast<double>(p.contacts.size());
    pushing += w.pushingPoints;
  }
  state.counters["contacts_per_pass"] = contacts / static_cast<double>(state.iterations());
  state.counters["pushing_per_pass"] = pushing / static_cast<double>(state.iterations());
  state.counters["contacts_per_s"] = benchmark::Counter(contacts, benchmark::Counter::kIsRate);
}
void contactWrenches(benchmark::State& state) {
  wrenchesOf(state, false);
}
void surfaceContactWrenches(benchmark::State& state) {
  wrenchesOf(state, true);
}

// voxel size in units of 10 µm (0.35 mm and 0.15 mm), and without or with a helper
BENCHMARK(contactWrenches)->ArgsProduct({{35, 15}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(surfaceContactWrenches)->ArgsProduct({{35, 15}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace voxhap
