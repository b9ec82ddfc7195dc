// SpaceMouseDevice through the real hidapi-hidraw path, on a SpaceNavigator that umockdev
// makes up: run by CTest as
//   umockdev-run --device tests/data/spacemouse/spacemouse.umockdev
//                --ioctl /dev/hidraw0=tests/data/spacemouse/spacemouse.ioctl
//                --script /dev/hidraw0=tests/data/spacemouse/spacemouse.script -- voxhap_umockdev_tests
// The script's reads come 500 ms apart; the test follows them by the parsed-report count.
// umockdev cannot unplug a scripted device (the pty stays open and the script rewinds at its
// end), so the vanishing device is tested with a fake transport in spacemouse_device_test.cpp.

#include <chrono>
#include <cstdlib>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "haptics/device/spacemouse_device.h"

namespace voxhap {
namespace {

using namespace std::chrono_literals;

constexpr double kDtS = 1e-3;
constexpr double kDeflection = 105.0 / 350.0;

bool underUmockdev() {
  return std::getenv("UMOCKDEV_DIR") != nullptr;
}

/// Waits (bounded) until `done` holds.
bool waitFor(const std::function<bool()>& done) {
  for (auto end = std::chrono::steady_clock::now() + 20s; std::chrono::steady_clock::now() < end;) {
    if (done()) return true;
    std::this_thread::sleep_for(1ms);
  }
  return done();
}

TEST(SpaceMouseUmockdev, EnumerationFindsTheSpaceNavigator) {
  if (!underUmockdev()) GTEST_SKIP() << "run under umockdev-run (see tests/CMakeLists.txt)";
  const std::vector<SpaceMouseInfo> found = listSpaceMice();
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].path, "/dev/hidraw0");
  EXPECT_EQ(found[0].vendorId, kVendorLogitech3Dconnexion);
  EXPECT_EQ(found[0].productId, 0xc626);
  EXPECT_EQ(found[0].name, "SpaceNavigator");
  EXPECT_TRUE(found[0].knownModel);
}

TEST(SpaceMouseUmockdev, ReplayedReportsMoveTheHandle) {
  if (!underUmockdev()) GTEST_SKIP() << "run under umockdev-run (see tests/CMakeLists.txt)";
  SpaceMouseConfig config;
  config.rate.deadZone = 0.05;
  config.rate.linearGainMPerS = 0.1;
  config.rate.angularGainRadPerS = 1.0;
  const Pose start{glm::dvec3(0.0, 0.2, 0.0), identityQuat()};
  SpaceMouseDevice device(start, DeviceLimits{}, config);
  EXPECT_EQ(device.openedAtStart().path, "/dev/hidraw0");
  const double speed = (kDeflection - 0.05) / 0.95;
  double t = 0.0;
  const auto run = [&](int frames) {
    for (int i = 0; i < frames; ++i) device.handlePose(t += kDtS);
  };

  // 1: translation to the right (device +x = view +x; view = world here)
  ASSERT_TRUE(waitFor([&] { return device.reportsParsed() >= 1; }));
  ASSERT_EQ(device.reportsParsed(), 1u) << "reports came faster than the test followed them";
  run(100);
  HandleVelocity v = device.handleVelocity(t);
  EXPECT_NEAR(v.linearWorld.x, 0.1 * speed, 1e-12);
  EXPECT_EQ(v.linearWorld.y, 0.0);
  EXPECT_EQ(v.angularWorld, glm::dvec3(0.0));
  EXPECT_GT(device.handlePose(t).position.x, 0.0);

  // 2: rotation about device +z (down) = view −y; the translation stays
  ASSERT_TRUE(waitFor([&] { return device.reportsParsed() >= 2; }));
  ASSERT_EQ(device.reportsParsed(), 2u);
  run(100);
  v = device.handleVelocity(t);
  EXPECT_NEAR(v.angularWorld.y, -speed, 1e-12);
  EXPECT_EQ(v.angularWorld.x, 0.0);
  EXPECT_NEAR(v.linearWorld.x, 0.1 * speed, 1e-12);

  // 3: one read, two reports: translation toward the user (view +z), rotation zero
  ASSERT_TRUE(waitFor([&] { return device.reportsParsed() >= 4; }));
  ASSERT_EQ(device.reportsParsed(), 4u);
  const double zBefore = device.handlePose(t).position.z;
  run(100);
  v = device.handleVelocity(t);
  EXPECT_NEAR(v.linearWorld.z, 0.1 * speed, 1e-12);
  EXPECT_EQ(v.linearWorld.x, 0.0);
  EXPECT_EQ(v.angularWorld, glm::dvec3(0.0));
  EXPECT_GT(device.handlePose(t).position.z, zBefore);

  // 4 and 5: button 1 down, then up in a read that also zeroes the translation
  ASSERT_TRUE(waitFor([&] { return device.reportsParsed() >= 7; }));
  ButtonEvent event;
  ASSERT_TRUE(device.tryPopButtonEvent(event));
  EXPECT_EQ(event.button, 1);
  EXPECT_TRUE(event.pressed);
  ASSERT_TRUE(device.tryPopButtonEvent(event));
  EXPECT_EQ(event.button, 1);
  EXPECT_FALSE(event.pressed);
  EXPECT_FALSE(device.tryPopButtonEvent(event));

  // after the last report the handle holds still
  const Pose held = device.handlePose(t += kDtS);
  run(1000);
  EXPECT_EQ(device.handlePose(t).position, held.position);
  EXPECT_EQ(device.handleVelocity(t).linearWorld, glm::dvec3(0.0));
  EXPECT_EQ(device.reportErrors(), 0u);
  EXPECT_TRUE(device.connected());
}

}  // namespace
}  // namespace voxhap
