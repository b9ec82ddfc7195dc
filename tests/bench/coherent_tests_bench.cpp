// Time-critical sampling throughput (issue 13): the frames of `voxhap bench rotation` at
// full MaxTravel without the rest of the step. The 25 mm ball turns about the x axis
// through its centre in its socket by the pair's MaxTravel a frame (its farthest point
// moves that far), and each iteration is one frame of its coherence: the chunk tests,
// the due points collected from the queues, and their tests (drift, voxmap lookup, queue
// moves), the ball seated as that benchmark seats it (seated_ball_model.h). Counters:
// point tests per second; tests, contacts and tests that drifted (no lookup) per frame.
// The second argument 1: a frame helper (a second thread, frame_helper.h) tests half.
#include <memory>

#include <benchmark/benchmark.h>
#include <glm/gtc/quaternion.hpp>

#include "haptics/coherence/pair_coherence.h"
#include "haptics/runtime/frame_helper.h"
#include "tests/bench/seated_ball_model.h"

namespace voxhap {
namespace {

void coherentTests(benchmark::State& state) {
  const SimModel& model = seatedBallModel(static_cast<double>(state.range(0)) * 1e-5);
  const PairModel& pair = model.pairs[0];
  const MovingObjectModel& ball = model.objects[0];
  const Pointshell& shell = ball.shell;
  const Voxmap& socket = model.voxmapOf(pair);
  const std::uint8_t forceLayer = pair.forceLayer(kDefaultForceLayer);
  const std::uint8_t sampledLayer = pair.params.sampledLayer(socket.encoding().maxValue());
  PairCoherence coherence(shell, socket.grid().voxelSizeM, forceLayer, socket.encoding().maxValue(), true);
  std::vector<std::uint32_t> due(shell.size());
  std::vector<std::uint32_t> dueChunks(shell.chunkCount());
  std::vector<PointContact> contacts(shell.size());
  const auto helper = state.range(1) ? std::make_unique<FrameHelper>() : nullptr;
  const double travelM = ball.maxTravelM;
  const double turnPerFrameRad = travelM / ball.shellRadiusM;
  const auto poseAt = [&](double angleRad) {
    const glm::dquat turn = glm::angleAxis(angleRad, glm::dvec3(1.0, 0.0, 0.0));
    return VoxelTransform::make(Pose{ball.body.comLocal - turn * ball.body.comLocal, turn}, socket.grid());
  };
  coherence.sortAll(shell, socket, poseAt(0.0), pair.fieldShifts, nullptr);
  coherence.endFrame(travelM);
  double angleRad = 0.0;
  double tests = 0.0;
  double found = 0.0;
  double drifted = 0.0;
  for (auto _ : state) {
    angleRad += turnPerFrameRad;
    const VoxelTransform transform = poseAt(angleRad);
    tests += coherence.updateChunks(shell, socket, transform, dueChunks, nullptr);
    const std::uint32_t n = coherence.collectDue(due);
    const PairCoherence::Tested t =
        coherence.testDue(shell, socket, transform, pair.fieldShifts, sampledLayer, std::span(due.data(), n),
                          contacts.data(), nullptr, helper.get());
    coherence.endFrame(travelM);
    tests += n;
    found += t.contacts;
    drifted += t.drifted;
  }
  const auto frames = static_cast<double>(state.iterations());
  state.counters["tests_per_frame"] = tests / frames;
  state.counters["contacts_per_frame"] = found / frames;
  state.counters["drifted_per_frame"] = drifted / frames;
  state.counters["tests_per_s"] = benchmark::Counter(tests, benchmark::Counter::kIsRate);
}
// voxel size in units of 10 µm (0.35 mm and 0.15 mm), and without or with a helper
BENCHMARK(coherentTests)->ArgsProduct({{35, 15}, {0, 1}})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace voxhap
