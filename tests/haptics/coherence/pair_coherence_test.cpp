// A pair's time-critical sampling with a frame helper (pair_coherence.h): the helper tests
// the last half of a frame's due points, and what the frame finds is the same as one
// thread's, contact for contact and queue for queue.
#include "haptics/coherence/pair_coherence.h"

#include <memory>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "haptics/runtime/frame_helper.h"
#include "support/helper_thread.h"
#include "tests/bench/seated_ball_model.h"

namespace voxhap {
namespace {

/// The 25 mm ball seated in its socket as `voxhap bench rotation` seats it: most of its
/// points are in contact or a layer beyond (mandatory), so both halves of a frame hold contacts.
constexpr double kVoxelM = 0.7e-3;

TEST(PairCoherence, AHelperFindsTheSameContactsAndQueuesAsOneThread) {
  const SimModel& model = seatedBallModel(kVoxelM);
  const PairModel& pair = model.pairs[0];
  const MovingObjectModel& ball = model.objects[0];
  const Pointshell& shell = ball.shell;
  const Voxmap& socket = model.voxmapOf(pair);
  const std::uint8_t sampledLayer = pair.params.sampledLayer(socket.encoding().maxValue());
  const auto poseAt = [&](double angleRad) {
    const glm::dquat turn = glm::angleAxis(angleRad, glm::normalize(glm::dvec3(1.0, 0.2, 0.0)));
    const glm::dvec3 shift(0.0, 1.5 * kVoxelM, 0.0);  // pressed to one side, loose on the other
    return VoxelTransform::make(Pose{ball.body.comLocal - turn * ball.body.comLocal + shift, turn},
                                socket.grid());
  };
  // one pair's coherence per run, the second with a helper
  test::onAThreadOfItsOwn([&] {
    FrameHelper helper;
    PairCoherence alone(shell, socket.grid().voxelSizeM, pair.forceLayer(kDefaultForceLayer),
                        socket.encoding().maxValue(), true);
    PairCoherence helped = alone;
    std::vector<std::uint32_t> due[2] = {std::vector<std::uint32_t>(shell.size()),
                                         std::vector<std::uint32_t>(shell.size())};
    std::vector<std::uint32_t> chunks(shell.chunkCount());
    std::vector<PointContact> contacts[2] = {std::vector<PointContact>(shell.size()),
                                             std::vector<PointContact>(shell.size())};
    PairCoherence* runs[2] = {&alone, &helped};
    for (PairCoherence* run : runs) {
      run->sortAll(shell, socket, poseAt(0.0), pair.fieldShifts, nullptr);
      run->endFrame(ball.maxTravelM);
    }
    std::uint64_t contactsInHelpersHalf = 0;
    int framesWithGaps = 0;
    const double turnPerFrameRad = ball.maxTravelM / ball.shellRadiusM;
    for (int frame = 1; frame <= 300; ++frame) {
      const VoxelTransform transform = poseAt(frame * turnPerFrameRad);
      PairCoherence::Tested tested[2];
      std::uint32_t dueCount[2];
      for (int r = 0; r < 2; ++r) {
        runs[r]->updateChunks(shell, socket, transform, chunks, nullptr);
        dueCount[r] = runs[r]->collectDue(due[r]);
        tested[r] = runs[r]->testDue(shell, socket, transform, pair.fieldShifts, sampledLayer,
                                     std::span(due[r].data(), dueCount[r]), contacts[r].data(), nullptr,
                                     r == 1 ? &helper : nullptr);
        runs[r]->endFrame(ball.maxTravelM);
      }
      ASSERT_EQ(dueCount[0], dueCount[1]) << "frame " << frame;
      ASSERT_GE(dueCount[0], PairCoherence::kHelpedTests)
          << "frame " << frame << ": too few for the helper to take a share";
      ASSERT_EQ(tested[0].contacts, tested[1].contacts) << "frame " << frame;
      EXPECT_EQ(tested[0].drifted, tested[1].drifted) << "frame " << frame;
      std::vector<bool> inHelpersHalf(shell.size(), false);  // due from the middle on
      for (std::uint32_t k = dueCount[0] / 2; k < dueCount[0]; ++k) inHelpersHalf[due[0][k]] = true;
      std::uint32_t inMyHalf = 0;
      for (std::uint32_t c = 0; c < tested[0].contacts; ++c) {
        const PointContact& a = contacts[0][c];
        const PointContact& b = contacts[1][c];
        ASSERT_TRUE(a.point == b.point && a.ijkVoxel == b.ijkVoxel && a.value == b.value)
            << "frame " << frame << ", contact " << c;
        contactsInHelpersHalf += inHelpersHalf[a.point] ? 1 : 0;
        inMyHalf += inHelpersHalf[a.point] ? 0 : 1;
      }
      // the helper's contacts then follow fewer than its first due point's index
      framesWithGaps += inMyHalf < dueCount[0] / 2 ? 1 : 0;
      for (std::uint32_t p = 0; p < shell.size(); p += 7) {
        ASSERT_EQ(alone.queues().queueOf(p), helped.queues().queueOf(p))
            << "frame " << frame << ", point " << p;
      }
    }
    EXPECT_GT(contactsInHelpersHalf, 1000u);
    EXPECT_GT(framesWithGaps, 100);
  });
}

}  // namespace
}  // namespace voxhap
