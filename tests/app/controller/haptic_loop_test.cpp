// The haptic loop in-process: a box over a plate, driven by commands from the test thread
// (standing in for the comms thread) while the haptic thread runs on real deadlines.
// Waits are bounded by frame counts and a wall-clock cap; nothing asserts a duration.

#include "app/controller/haptic_loop.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include "haptics/coherence/pair_coherence.h"
#include "haptics/core/error.h"
#include "haptics/geometry/mesh_builder.h"
#include "haptics/runtime/frame_clock.h"
#include "support/contact_scenes.h"
#include "support/helper_thread.h"

namespace voxhap::controller {
namespace {

using namespace std::chrono_literals;

class HapticLoopTest : public ::testing::Test {
protected:
  void SetUp() override {
    scene_.objects.push_back(test::plate());
    scene_.objects.push_back(test::meshObject("box", ObjectRole::Dynamic, [](TriangleMesh& m) {
      appendBox(m, test::at(0.0, 0.0, 0.012), glm::dvec3(0.01));  // 2 mm above the plate
    }));
    SceneModelOptions options = test::ampleCapacityOptions();
    options.staticVoxelSizeM = 1e-3;
    options.pointSpacingM = 1e-3;
    model_ = buildSceneModel(scene_, {"box"}, options);
    HapticLoopOptions loopOptions;
    loopOptions.realtime = false;
    loop_ = std::make_unique<HapticLoop>(model_, makeSimState(model_), nullptr, loopOptions);
    loop_->start();
  }

  /// A copy of the newest snapshot once `done` holds for it, or the last one after 10 s.
  template <class Done>
  FrameSnapshot waitFor(Done done) {
    const auto giveUp = std::chrono::steady_clock::now() + 10s;
    while (!done(loop_->latest()) && std::chrono::steady_clock::now() < giveUp)
      std::this_thread::sleep_for(1ms);
    return loop_->latest();
  }

  /// A script that holds the handle `dropM` below the box's place from the start.
  static ScriptedDevice pressingDevice(double dropM, const SimModel& model) {
    Pose down;
    down.position.z = -dropM;
    return ScriptedDevice(MotionScript({{0.0, down}, {100.0, down}}, "press"), model.deviceLimits);
  }

  Scene scene_;
  SimModel model_;
  std::unique_ptr<HapticLoop> loop_;
};

// a device that remembers where each grab found its object, as rate control starts there
class GrabRecordingDevice final : public HapticDevice {
public:
  explicit GrabRecordingDevice(const DeviceLimits& limits) : limits_(limits) {}
  Pose handlePose(double) noexcept override { return start; }
  HandleVelocity handleVelocity(double) noexcept override { return {}; }
  void setFeedback(const CouplingWrench&) noexcept override {}
  const DeviceLimits& limits() const noexcept override { return limits_; }
  void grabbed(const Pose& objectWorld) noexcept override {
    start = objectWorld;
    ++grabs;
  }
  Pose start;
  std::atomic<int> grabs{0};

private:
  DeviceLimits limits_;
};

TEST_F(HapticLoopTest, AGrabTellsTheDeviceWhereItsObjectIs) {
  auto press = std::make_unique<ScriptedDevice>(pressingDevice(0.005, model_));
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Grab, 0, press.get(), 0, {}}));
  const FrameSnapshot moved =
      waitFor([](const FrameSnapshot& s) { return s.objects[0].pose.position.z < -1e-4; });
  ASSERT_LT(moved.objects[0].pose.position.z, -1e-4);
  GrabRecordingDevice device(model_.deviceLimits);
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Grab, 0, &device, 0, {}}));  // replaces the script
  waitFor([&](const FrameSnapshot&) { return device.grabs.load() > 0; });
  ASSERT_EQ(device.grabs.load(), 1);
  EXPECT_LT(device.start.position.z, -1e-4);  // where the script had pushed it, not its place in the scene
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Release, 0, nullptr, 0, {}}));
  waitFor([](const FrameSnapshot& s) { return !s.objects[0].held; });
  loop_->stop();
}

TEST_F(HapticLoopTest, FramesAdvanceAndAGrabbedBoxIsPressedOntoThePlate) {
  const std::uint64_t start = waitFor([](const FrameSnapshot& s) { return s.frame >= 10; }).frame;
  EXPECT_GE(start, 10u);
  auto device = std::make_unique<ScriptedDevice>(pressingDevice(0.005, model_));
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Grab, 0, device.get(), 0, {}}));
  const FrameSnapshot pressed = waitFor([](const FrameSnapshot& s) {
    return s.objects[0].held && s.objects[0].contacts > 0 && s.objects[0].pose.position.z < 0.0;
  });
  ASSERT_TRUE(pressed.objects[0].held);
  EXPECT_GT(pressed.objects[0].contacts, 0u);
  EXPECT_LT(pressed.objects[0].pose.position.z, 0.0);  // it moved down towards the handle
  EXPECT_NEAR(pressed.objects[0].handle.position.z, -0.005, 1e-12);
  const FrameSnapshot resting =
      waitFor([&](const FrameSnapshot& s) { return s.frame > pressed.frame + 300; });
  EXPECT_GT(resting.objects[0].forceWorld.z, 0.0);  // the plate pushes back up

  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Release, 0, nullptr, 0, {}}));
  const FrameSnapshot released = waitFor([](const FrameSnapshot& s) { return !s.objects[0].held; });
  EXPECT_FALSE(released.objects[0].held);
  EXPECT_EQ(loop_->takeRetired(), device.get());
  EXPECT_EQ(loop_->takeRetired(), nullptr);
}

TEST_F(HapticLoopTest, TheForceLayerChangesAtTheNextFrame) {
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::SetForceLayer, 0, nullptr, 3, {}}));
  EXPECT_EQ(waitFor([](const FrameSnapshot& s) { return s.forceLayer == 3; }).forceLayer, 3u);
}

TEST_F(HapticLoopTest, TheCouplingTakesTheGainsSetForIt) {
  LoopCommand slack{LoopCommand::Kind::SetCouplingGains, 0, nullptr, 0, CouplingGains{}};  // no spring
  ASSERT_TRUE(loop_->post(slack));
  auto device = std::make_unique<ScriptedDevice>(pressingDevice(0.005, model_));
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Grab, 0, device.get(), 0, {}}));
  const FrameSnapshot held = waitFor([](const FrameSnapshot& s) { return s.objects[0].held; });
  const FrameSnapshot unpulled = waitFor([&](const FrameSnapshot& s) { return s.frame > held.frame + 300; });
  EXPECT_GT(unpulled.objects[0].pose.position.z, -1e-6);  // held, but nothing pulls it down

  LoopCommand stiff = slack;
  stiff.gains = model_.objects[0].gains;
  ASSERT_TRUE(loop_->post(stiff));
  const FrameSnapshot pulled =
      waitFor([](const FrameSnapshot& s) { return s.objects[0].pose.position.z < -1e-4; });
  EXPECT_LT(pulled.objects[0].pose.position.z, -1e-4);
  loop_->stop();  // before the device goes
}

TEST_F(HapticLoopTest, ObjectsStartWhereTheInitialStatePutsThem) {
  loop_->stop();
  SimState start = makeSimState(model_);
  Pose raisedAndTurned;
  raisedAndTurned.position.z = 0.01;  // 12 mm above the plate, out of reach of its force layer
  raisedAndTurned.orientation = glm::angleAxis(0.5, glm::dvec3(0.0, 0.0, 1.0));
  start.bodies[0] = restingState(model_.objects[0].body, raisedAndTurned);
  HapticLoopOptions options;
  options.realtime = false;
  loop_ = std::make_unique<HapticLoop>(model_, start, nullptr, options);
  EXPECT_NEAR(loop_->latest().objects[0].pose.position.z, 0.01, 1e-12);  // before the first frame too
  loop_->start();
  const FrameSnapshot later = waitFor([](const FrameSnapshot& s) { return s.frame >= 100; });
  EXPECT_NEAR(later.objects[0].pose.position.z, 0.01, 1e-9);
  EXPECT_NEAR(later.objects[0].pose.orientation.w, std::cos(0.25), 1e-9);
}

TEST_F(HapticLoopTest, InASessionItMovesWhatItOwnsFollowsWhatOthersOwnAndHoldsTheRest) {
  loop_->stop();
  HapticLoopOptions options;
  options.realtime = false;
  options.localPeer = 7;
  loop_ = std::make_unique<HapticLoop>(model_, makeSimState(model_), nullptr, options);
  loop_->start();
  const Pose placed = loop_->latest().objects[0].pose;
  // nobody's: it stays where it is, gravity or not
  const FrameSnapshot held = waitFor([](const FrameSnapshot& s) { return s.frame >= 200; });
  EXPECT_EQ(held.objects[0].pose.position, placed.position);
  EXPECT_EQ(held.objects[0].owner, kNoPeer);

  // peer 9's: it goes where 9's stream puts it; a stream of another peer is ignored
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::SetOwner, 0, nullptr, 9, {}}));
  waitFor([](const FrameSnapshot& s) { return s.objects[0].owner == 9; });
  RemoteUpdate update;
  update.object = 0;
  update.peer = 8;
  update.sample.body = held.objects[0].body;
  update.sample.body.comWorld.y += 0.02;
  update.sample.sentUs = 1;
  update.arrivalUs = monotonicTime().nowNs() / 1000;
  ASSERT_TRUE(loop_->postRemote(update));
  update.peer = 9;
  update.sample.body.comWorld.y = held.objects[0].body.comWorld.y;
  update.sample.body.comWorld.x += 0.005;
  ASSERT_TRUE(loop_->postRemote(update));
  const FrameSnapshot followed =
      waitFor([](const FrameSnapshot& s) { return s.objects[0].pose.position.x > 0.0049; });
  EXPECT_NEAR(followed.objects[0].pose.position.x, 0.005, 1e-12);
  EXPECT_EQ(followed.objects[0].pose.position.y, placed.position.y);

  // ours: integrated here, so a handle pressing it down moves it towards the plate
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::SetOwner, 0, nullptr, 7, {}}));
  auto device = std::make_unique<ScriptedDevice>(pressingDevice(0.01, model_));
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Grab, 0, device.get(), 0, {}}));
  const FrameSnapshot pressed = waitFor(
      [&](const FrameSnapshot& s) { return s.objects[0].pose.position.z < placed.position.z - 2e-4; });
  EXPECT_LT(pressed.objects[0].pose.position.z, placed.position.z - 2e-4);
  loop_->stop();  // before the device goes
}

TEST_F(HapticLoopTest, ASharedObjectIsIntegratedHereAndPulledTowardsAnotherSharersInstance) {
  HapticLoopOptions options;
  options.realtime = false;
  options.localPeer = 7;
  loop_ = std::make_unique<HapticLoop>(model_, makeSimState(model_), nullptr, options);
  loop_->start();
  const RigidBodyState placed = waitFor([](const FrameSnapshot& s) { return s.frame >= 10; }).objects[0].body;
  // sharer 9 owns it (the lowest sharer); this peer shares it too, without the passivity
  // controller (with it, the coupling gives out no energy that no port has put in)
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::SetOwner, 0, nullptr, 9, {}}));
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Share, 0, nullptr, 0, {}}));
  // 9's instance 5 mm along y, streamed at 100 Hz from this thread (the comms thread's
  // place) with its delay measured at once
  RemoteUpdate delay;
  delay.kind = RemoteUpdate::Kind::SharedDelay;
  delay.peer = 9;
  RemoteUpdate state;
  state.kind = RemoteUpdate::Kind::SharedState;
  state.peer = 9;
  state.sample.body = placed;
  state.sample.body.comWorld.y += 0.005;
  FrameSnapshot pulled;
  for (int i = 0; i < 300; ++i) {
    const std::int64_t nowUs = monotonicTime().nowNs() / 1000;
    state.sample.sentUs = state.arrivalUs = nowUs;
    ASSERT_TRUE(loop_->postRemote(state));
    ASSERT_TRUE(loop_->postRemote(delay));
    std::this_thread::sleep_for(10ms);
    pulled = loop_->latest();
    if (pulled.objects[0].body.comWorld.y > placed.comWorld.y + 0.004) break;
  }
  const SharedObjectPort::Frame& port = pulled.objects[0].port;
  EXPECT_TRUE(pulled.objects[0].shared);
  EXPECT_EQ(port.counted, 1u);
  EXPECT_GT(port.coupling.stiffnessShare, 0.0);
  EXPECT_FALSE(port.coupling.divergent);
  EXPECT_GT(pulled.objects[0].body.comWorld.y, placed.comWorld.y + 0.004);  // integrated here, pulled
  EXPECT_EQ(pulled.objects[0].owner, 9u);
  // 9 stops sharing: its instance fades out of the coupling within a second or so
  RemoteUpdate left;
  left.kind = RemoteUpdate::Kind::SharedLeft;
  left.peer = 9;
  ASSERT_TRUE(loop_->postRemote(left));
  const FrameSnapshot alone = waitFor([](const FrameSnapshot& s) { return s.objects[0].port.counted == 0; });
  EXPECT_EQ(alone.objects[0].port.counted, 0u);
  EXPECT_EQ(alone.objects[0].port.wrench.forceWorld, glm::dvec3(0.0));
}

TEST_F(HapticLoopTest, StopRetiresTheDevicesStillHeldAndKeepsItsStatistics) {
  auto device = std::make_unique<ScriptedDevice>(pressingDevice(0.0, model_));
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Grab, 0, device.get(), 0, {}}));
  waitFor([](const FrameSnapshot& s) { return s.objects[0].held && s.frame > 200; });
  loop_->stop();
  loop_->stop();  // a second stop does nothing
  EXPECT_EQ(loop_->takeRetired(), device.get());
  EXPECT_GT(loop_->periodStats().count(), 200u);
  EXPECT_EQ(loop_->periodStats().count() + 1, loop_->computeStats().count());
  EXPECT_FALSE(loop_->realtime().fifo.ok);  // not asked for
}

/// Threads of this process now.
std::size_t threadCount() {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator("/proc/self/task"),
                                                std::filesystem::directory_iterator()));
}

// --frame-helper of the controller: the helper is made by the haptic thread on a CPU of
// its own, shares the frames of a finely pointed box (0.25 mm: nearly every frame has
// more than 1,024 tests; at 0.5 mm only the first, which a poll once missed) pressed onto
// the plate, and ends with the loop
TEST_F(HapticLoopTest, AFrameHelperComesWithTheHapticThreadAndEndsWithIt) {
  if (const char* why = test::noSpareCore()) GTEST_SKIP() << why;
  loop_->stop();
  SceneModelOptions fine = test::ampleCapacityOptions();
  fine.staticVoxelSizeM = 1e-3;
  fine.pointSpacingM = 0.25e-3;
  const SimModel model = buildSceneModel(scene_, {"box"}, fine);
  const std::size_t before = threadCount();
  HapticLoopOptions options;
  options.realtime = false;
  options.frameHelper = true;
  HapticLoop helped(model, makeSimState(model), nullptr, options);
  helped.start();
  EXPECT_GE(helped.frameHelperCpu(), 0);
  EXPECT_EQ(threadCount(), before + 2) << "the haptic thread and its helper";
  auto device = std::make_unique<ScriptedDevice>(pressingDevice(0.005, model));
  ASSERT_TRUE(helped.post({LoopCommand::Kind::Grab, 0, device.get(), 0, {}}));
  std::uint32_t mostTested = 0;  // in the frames seen
  const auto giveUp = std::chrono::steady_clock::now() + 10s;
  while (helped.latest().frame < 1000 && std::chrono::steady_clock::now() < giveUp) {
    mostTested = std::max(mostTested, helped.latest().objects[0].tested);
    std::this_thread::sleep_for(1ms);
  }
  const FrameSnapshot resting = helped.latest();
  EXPECT_GE(resting.frame, 1000u);
  EXPECT_GE(mostTested, PairCoherence::kHelpedTests) << "frames large enough for the helper";
  EXPECT_GT(resting.objects[0].forceWorld.z, 0.0);  // the plate pushes back up
  helped.stop();
  EXPECT_EQ(threadCount(), before);
}

// where the haptic thread may run on one CPU only there is no spare core: start() says so
// and leaves no thread behind
TEST_F(HapticLoopTest, AFrameHelperWithoutASpareCoreIsRefusedAtStart) {
  loop_->stop();
  std::thread([&] {
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(static_cast<std::size_t>(sched_getcpu()), &one);
    ASSERT_EQ(pthread_setaffinity_np(pthread_self(), sizeof(one), &one), 0);
    const std::size_t before = threadCount();
    HapticLoopOptions options;
    options.realtime = false;
    options.frameHelper = true;
    HapticLoop refused(model_, makeSimState(model_), nullptr, options);
    try {
      refused.start();
      ADD_FAILURE() << "started with a frame helper on one CPU";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("spare core"), std::string::npos) << e.what();
    }
    EXPECT_EQ(threadCount(), before);
  }).join();
}

/// Keeps the calling thread busy (never sleeping) for `duration`.
void busyFor(std::chrono::nanoseconds duration) {
  const auto until = std::chrono::steady_clock::now() + duration;
  while (std::chrono::steady_clock::now() < until) {
  }
}

// a device whose first frames each take longer than the period, so that its loop never
// sleeps until it has done them; when it has, it notes how far every other such device got
class OverrunningDevice final : public HapticDevice {
public:
  OverrunningDevice(const DeviceLimits& limits, const std::vector<std::unique_ptr<OverrunningDevice>>& all)
      : limits_(limits), all_(all) {}
  Pose handlePose(double) noexcept override {
    if (frames.load() < kOverrunFrames) {
      busyFor(1500us);
      if (frames.fetch_add(1) + 1 == kOverrunFrames) {
        for (std::size_t i = 0; i < all_.size(); ++i) othersWhenDone[i] = all_[i]->frames.load();
      }
    }
    return {};
  }
  HandleVelocity handleVelocity(double) noexcept override { return {}; }
  void setFeedback(const CouplingWrench&) noexcept override {}
  const DeviceLimits& limits() const noexcept override { return limits_; }

  static constexpr int kOverrunFrames = 300;
  std::atomic<int> frames{0};
  std::vector<int> othersWhenDone;  ///< one per device, sized before the grab; written once by its loop

private:
  DeviceLimits limits_;
  const std::vector<std::unique_ptr<OverrunningDevice>>& all_;
};

// Under SCHED_FIFO a thread is never preempted by one of its own priority: loops whose
// frames all overrun never sleep, and with more of them than cores one would get no frame
// at all until the others stopped overrunning (one peer of `voxhap demo` stood still for
// 12.5 s). Each loop yields once a frame, so all of them go on together.
TEST_F(HapticLoopTest, LoopsThatOverrunUnderFifoShareTheCores) {
  loop_->stop();
  const std::size_t count = std::max(2u, std::thread::hardware_concurrency()) + 1;
  std::vector<std::unique_ptr<OverrunningDevice>> devices;
  for (std::size_t i = 0; i < count; ++i)
    devices.push_back(std::make_unique<OverrunningDevice>(model_.deviceLimits, devices));
  for (auto& d : devices) d->othersWhenDone.resize(count, -1);
  std::vector<std::unique_ptr<HapticLoop>> loops;
  for (std::size_t i = 0; i < count; ++i) {
    loops.push_back(std::make_unique<HapticLoop>(model_, makeSimState(model_), nullptr, HapticLoopOptions{}));
    loops.back()->start();
    if (!loops.back()->realtime().fifo.ok) {
      GTEST_SKIP() << "SCHED_FIFO refused here: " << loops.back()->realtime().fifo.error;
    }
  }
  for (std::size_t i = 0; i < count; ++i)
    ASSERT_TRUE(loops[i]->post({LoopCommand::Kind::Grab, 0, devices[i].get(), 0, {}}));
  const auto giveUp = std::chrono::steady_clock::now() + 30s;
  const auto allDone = [&] {
    return std::all_of(devices.begin(), devices.end(),
                       [](const auto& d) { return d->frames.load() >= OverrunningDevice::kOverrunFrames; });
  };
  while (!allDone() && std::chrono::steady_clock::now() < giveUp) std::this_thread::sleep_for(10ms);
  for (auto& loop : loops) loop->stop();
  ASSERT_TRUE(allDone());
  // when any loop had done its overrunning frames, every other had done a third of its own
  for (const auto& d : devices) {
    for (const int others : d->othersWhenDone) EXPECT_GE(others, OverrunningDevice::kOverrunFrames / 3);
  }
}

// a device whose first frames each take longer than a period of 4 ms; it notes the
// scheduling policy of the thread that calls it
class SlowThenQuickDevice final : public HapticDevice {
public:
  explicit SlowThenQuickDevice(const DeviceLimits& limits) : limits_(limits) {}
  Pose handlePose(double) noexcept override {
    const int frame = frames.fetch_add(1);
    if (frame < kSlowFrames) busyFor(6ms);
    policy.store(sched_getscheduler(0));
    if (frame == kSlowFrames - 1) policyAtLastSlowFrame.store(policy.load());
    return {};
  }
  HandleVelocity handleVelocity(double) noexcept override { return {}; }
  void setFeedback(const CouplingWrench&) noexcept override {}
  const DeviceLimits& limits() const noexcept override { return limits_; }

  static constexpr int kSlowFrames = 100;
  std::atomic<int> frames{0};
  std::atomic<int> policy{-1};
  std::atomic<int> policyAtLastSlowFrame{-1};

private:
  DeviceLimits limits_;
};

// A loop whose frames overrun gives SCHED_FIFO up (else it would leave ordinary threads,
// its own peer's comms among them, only the kernel's throttling remainder), and takes it
// again once its frames are quick (FifoHold).
TEST_F(HapticLoopTest, ALoopWhoseFramesOverrunGivesSchedFifoUpUntilTheyAreQuickAgain) {
  loop_->stop();
  // a period long enough that a sanitizer's frames take less than half of it
  HapticLoopOptions options;
  options.periodNs = 4'000'000;
  loop_ = std::make_unique<HapticLoop>(model_, makeSimState(model_), nullptr, options);
  loop_->start();
  if (!loop_->realtime().fifo.ok) GTEST_SKIP() << "SCHED_FIFO refused here: " << loop_->realtime().fifo.error;
  SlowThenQuickDevice device(model_.deviceLimits);
  ASSERT_TRUE(loop_->post({LoopCommand::Kind::Grab, 0, &device, 0, {}}));
  // patient: the quick frames must come 1000 in a row, and on a busy machine a thread
  // without SCHED_FIFO is often preempted within one
  const auto giveUp = std::chrono::steady_clock::now() + 60s;
  const auto waitUntil = [&](auto done) {
    while (!done() && std::chrono::steady_clock::now() < giveUp) std::this_thread::sleep_for(1ms);
  };
  waitUntil([&] { return device.policyAtLastSlowFrame.load() != -1; });
  EXPECT_EQ(device.policyAtLastSlowFrame.load(), SCHED_OTHER);
  waitUntil([&] { return loop_->latest().fifoGivenUp > 0; });
  EXPECT_EQ(loop_->latest().fifoGivenUp, 1u);
  waitUntil([&] { return loop_->latest().fifoHeld; });
  ASSERT_TRUE(loop_->latest().fifoHeld);
  const int framesThen = device.frames.load();
  waitUntil([&] { return device.frames.load() > framesThen + 10; });
  EXPECT_EQ(device.policy.load(), SCHED_FIFO);
  EXPECT_EQ(loop_->latest().fifoGivenUp, 1u);
  loop_->stop();
}

TEST_F(HapticLoopTest, AFullQueueRefusesCommandsWithoutBlocking) {
  loop_->stop();  // nobody takes commands any more
  int accepted = 0;
  for (int i = 0; i < 1000; ++i)
    accepted += loop_->post({LoopCommand::Kind::SetForceLayer, 0, nullptr, 4, {}}) ? 1 : 0;
  EXPECT_EQ(accepted, 256);  // HapticLoopOptions::commandCapacity
}

}  // namespace
}  // namespace voxhap::controller
