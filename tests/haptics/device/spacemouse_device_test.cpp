#include "haptics/device/spacemouse_device.h"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "support/allocation_counter.h"

namespace voxhap {
namespace {

using namespace std::chrono_literals;

/// What the fake hands out: bytes for one read, or a read error (the device unplugged).
struct FakeRead {
  std::vector<std::uint8_t> bytes;
  bool error = false;
};

/// An in-process HID transport: the test sets what enumeration lists and queues reads;
/// the device's reader thread takes them.
class FakeTransport final : public HidTransport {
public:
  struct Shared {
    std::mutex mutex;
    std::condition_variable changed;
    std::vector<HidDeviceInfo> present;
    std::deque<FakeRead> reads;
    std::string openPath;
    int opens = 0;
    int enumerations = 0;
    bool failOpen = false;
  };

  explicit FakeTransport(std::shared_ptr<Shared> shared) : shared_(std::move(shared)) {}

  std::vector<HidDeviceInfo> enumerate() override {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    ++shared_->enumerations;
    return shared_->present;
  }
  bool open(const std::string& path) override {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    if (shared_->failOpen) return false;
    shared_->openPath = path;
    ++shared_->opens;
    return true;
  }
  int read(std::span<std::uint8_t> buffer, int timeoutMs) override {
    std::unique_lock<std::mutex> lock(shared_->mutex);
    shared_->changed.wait_for(lock, std::chrono::milliseconds(timeoutMs),
                              [&] { return !shared_->reads.empty(); });
    if (shared_->reads.empty()) return 0;
    FakeRead next = std::move(shared_->reads.front());
    shared_->reads.pop_front();
    if (next.error) {
      shared_->openPath.clear();
      return -1;
    }
    const std::size_t n = std::min(buffer.size(), next.bytes.size());
    std::copy_n(next.bytes.begin(), n, buffer.begin());
    return static_cast<int>(n);
  }
  void close() noexcept override {}
  std::string lastError() const override { return "Permission denied"; }

private:
  std::shared_ptr<Shared> shared_;
};

/// A hotplug source the test fires by hand (on the test's thread).
class FakeHotplug final : public HotplugSource {
public:
  struct Shared {
    std::mutex mutex;
    ArrivalFn onArrival;  // set by start, cleared by the destructor
    bool active = true;
  };

  explicit FakeHotplug(std::shared_ptr<Shared> shared) : shared_(std::move(shared)) {}
  ~FakeHotplug() override {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->onArrival = nullptr;
  }
  void start(ArrivalFn onArrival) override {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->onArrival = std::move(onArrival);
  }
  bool active() const noexcept override { return shared_->active; }
  std::string status() const override { return shared_->active ? "fake hotplug on" : "fake hotplug off"; }

  /// Reports an arrival as the source's thread would; false when not started or gone.
  static bool fire(Shared& shared) {
    std::lock_guard<std::mutex> lock(shared.mutex);
    if (!shared.onArrival) return false;
    shared.onArrival();
    return true;
  }

private:
  std::shared_ptr<Shared> shared_;
};

HidDeviceInfo navigator() {
  return HidDeviceInfo{"/dev/hidraw7",           kVendorLogitech3Dconnexion, 0xc626,
                       kUsagePageGenericDesktop, kUsageMultiAxisController,  "SpaceNavigator"};
}

HidDeviceInfo keyboard() {
  return HidDeviceInfo{"/dev/hidraw0", 0x1234, 0x0001, kUsagePageGenericDesktop, 0x06, "Keyboard"};
}

std::vector<std::uint8_t> report(std::uint8_t id, int a, int b, int c) {
  std::vector<std::uint8_t> out{id};
  for (int v : {a, b, c}) {
    const auto bits = static_cast<std::uint16_t>(static_cast<std::int16_t>(v));
    out.push_back(static_cast<std::uint8_t>(bits & 0xff));
    out.push_back(static_cast<std::uint8_t>(bits >> 8));
  }
  return out;
}

class SpaceMouseDeviceTest : public ::testing::Test {
protected:
  void SetUp() override {
    shared_->present = {keyboard(), navigator()};
    config_.rate.deadZone = 0.0;
    config_.rate.linearGainMPerS = 0.1;
    config_.rate.angularGainRadPerS = 1.0;
    config_.readTimeoutMs = 5;
    config_.rescanPeriodS = 0.02;
  }

  std::unique_ptr<SpaceMouseDevice> makeDevice(const Pose& start = Pose{}) {
    return std::make_unique<SpaceMouseDevice>(start, DeviceLimits{}, config_,
                                              std::make_unique<FakeTransport>(shared_),
                                              std::make_unique<FakeHotplug>(hotplug_));
  }

  /// Makes the device vanish (from enumeration, and as a read error) and waits for the loss.
  void unplug(SpaceMouseDevice& device) {
    {
      std::lock_guard<std::mutex> lock(shared_->mutex);
      shared_->present = {keyboard()};
    }
    queue({{}, true});
    ASSERT_TRUE(waitFor([&] { return !device.connected(); }));
  }

  void replug() {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->present = {keyboard(), navigator()};
  }

  void queue(FakeRead read) {
    {
      std::lock_guard<std::mutex> lock(shared_->mutex);
      shared_->reads.push_back(std::move(read));
    }
    shared_->changed.notify_all();
  }

  /// Waits (bounded) until `done` holds; false on time-out.
  static bool waitFor(const std::function<bool()>& done) {
    for (auto end = std::chrono::steady_clock::now() + 10s; std::chrono::steady_clock::now() < end;) {
      if (done()) return true;
      std::this_thread::sleep_for(1ms);
    }
    return done();
  }

  std::shared_ptr<FakeTransport::Shared> shared_ = std::make_shared<FakeTransport::Shared>();
  std::shared_ptr<FakeHotplug::Shared> hotplug_ = std::make_shared<FakeHotplug::Shared>();
  SpaceMouseConfig config_;
};

TEST_F(SpaceMouseDeviceTest, NoneFoundIsAClearError) {
  shared_->present = {keyboard(), keyboard()};
  shared_->present[1].path = "/dev/hidraw1";
  try {
    makeDevice();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "no SpaceMouse found: 2 HID devices seen, none with usage 0x01/0x08 or a known id");
  }
}

TEST_F(SpaceMouseDeviceTest, OpenFailureNamesTheDevice) {
  shared_->failOpen = true;
  try {
    makeDevice();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "cannot open SpaceNavigator (046d:c626) at /dev/hidraw7: Permission denied"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(SpaceMouseDeviceTest, UnknownModelIsFoundByItsUsage) {
  HidDeviceInfo unknown{
      "/dev/hidraw4", 0x1111, 0x2222, kUsagePageGenericDesktop, kUsageMultiAxisController, ""};
  // hidapi lists one path per collection: the same path again with another usage
  HidDeviceInfo sameOther = unknown;
  sameOther.usage = 0x05;
  const SpaceMouseScan scan = findSpaceMice({keyboard(), sameOther, unknown});
  ASSERT_EQ(scan.spaceMice.size(), 1u);
  EXPECT_EQ(scan.hidDevicesSeen, 2u);
  EXPECT_EQ(scan.spaceMice[0].path, "/dev/hidraw4");
  EXPECT_FALSE(scan.spaceMice[0].knownModel);
  shared_->present = {keyboard(), unknown};
  auto device = makeDevice();
  EXPECT_EQ(device->openedAtStart().path, "/dev/hidraw4");
}

TEST_F(SpaceMouseDeviceTest, DeflectionMovesTheHandleAndButtonsGiveEdges) {
  const Pose start{glm::dvec3(0.5, 0.0, 0.0), identityQuat()};
  auto device = makeDevice(start);
  EXPECT_TRUE(device->connected());
  EXPECT_EQ(device->handlePose(0.0).position, start.position);

  queue({report(1, 350, 0, 0)});  // full right
  ASSERT_TRUE(waitFor([&] { return device->reportsParsed() >= 1; }));
  double t = 0.0;
  for (int i = 0; i < 100; ++i) device->handlePose(t += 1e-3);
  EXPECT_NEAR(device->handlePose(t).position.x, 0.5 + 0.1 * 0.1, 1e-12);
  EXPECT_NEAR(device->handleVelocity(t).linearWorld.x, 0.1, 1e-15);

  std::vector<std::uint8_t> coalesced = report(1, 0, 0, 0);
  const std::vector<std::uint8_t> buttons{3, 0x01, 0x00};
  coalesced.insert(coalesced.end(), buttons.begin(), buttons.end());
  queue({coalesced});
  queue({{3, 0x00, 0x00}});
  ASSERT_TRUE(waitFor([&] { return device->reportsParsed() >= 4; }));
  device->handlePose(t += 1e-3);
  EXPECT_EQ(device->handleVelocity(t).linearWorld, glm::dvec3(0.0));

  ButtonEvent event;
  ASSERT_TRUE(device->tryPopButtonEvent(event));
  EXPECT_EQ(event.button, 1);
  EXPECT_TRUE(event.pressed);
  ASSERT_TRUE(device->tryPopButtonEvent(event));
  EXPECT_EQ(event.button, 1);
  EXPECT_FALSE(event.pressed);
  EXPECT_FALSE(device->tryPopButtonEvent(event));
  EXPECT_EQ(device->reportErrors(), 0u);
}

TEST_F(SpaceMouseDeviceTest, VanishedDeviceHoldsStillAndIsPickedUpAgain) {
  auto device = makeDevice();
  queue({report(1, 0, 0, 175)});  // device z: down → view −y
  ASSERT_TRUE(waitFor([&] { return device->reportsParsed() >= 1; }));
  double t = 0.0;
  for (int i = 0; i < 10; ++i) device->handlePose(t += 1e-3);
  const double yMoving = device->handlePose(t).position.y;
  EXPECT_LT(yMoving, 0.0);

  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->present = {keyboard()};
  }
  queue({{}, true});
  ASSERT_TRUE(waitFor([&] { return !device->connected(); }));
  EXPECT_EQ(device->disconnects(), 1u);
  const Pose held = device->handlePose(t += 1e-3);
  for (int i = 0; i < 100; ++i) device->handlePose(t += 1e-3);
  EXPECT_EQ(device->handlePose(t).position, held.position);
  EXPECT_EQ(device->handleVelocity(t).linearWorld, glm::dvec3(0.0));

  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->present = {keyboard(), navigator()};
  }
  ASSERT_TRUE(waitFor([&] { return device->connected(); }));
  EXPECT_EQ(device->reconnects(), 1u);
  queue({report(1, 350, 0, 0)});
  ASSERT_TRUE(waitFor([&] { return device->reportsParsed() >= 2; }));
  for (int i = 0; i < 10; ++i) device->handlePose(t += 1e-3);
  EXPECT_GT(device->handlePose(t).position.x, held.position.x);
  EXPECT_EQ(device->handlePose(t).position.y, held.position.y);
}

TEST_F(SpaceMouseDeviceTest, HotplugArrivalEnumeratesAtOnce) {
  config_.rescanPeriodS = 30.0;  // the periodic rescan cannot be what finds it
  auto device = makeDevice();
  EXPECT_TRUE(device->hotplugActive());
  EXPECT_EQ(device->hotplugStatus(), "fake hotplug on; enumerating on arrival and every 30 s");
  unplug(*device);
  replug();
  // present again, but nothing looks until the arrival
  std::this_thread::sleep_for(50ms);
  EXPECT_FALSE(device->connected());
  ASSERT_TRUE(FakeHotplug::fire(*hotplug_));
  const auto fired = std::chrono::steady_clock::now();
  while (!device->connected() && std::chrono::steady_clock::now() - fired < 2s)
    std::this_thread::sleep_for(1ms);
  EXPECT_TRUE(device->connected()) << "no reconnect within 2 s of the arrival";
  EXPECT_EQ(device->reconnects(), 1u);
  EXPECT_EQ(device->hotplugArrivals(), 1u);
}

TEST_F(SpaceMouseDeviceTest, ArrivalBeforeTheNodeIsThereIsCaughtByTheRescan) {
  config_.rescanPeriodS = 0.2;
  auto device = makeDevice();
  unplug(*device);
  // the USB device arrives before its hidraw node: the enumeration at the arrival misses it
  const auto enumerations = [&] {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    return shared_->enumerations;
  };
  const int before = enumerations();
  ASSERT_TRUE(FakeHotplug::fire(*hotplug_));
  ASSERT_TRUE(waitFor([&] { return enumerations() > before; }));
  EXPECT_FALSE(device->connected());
  replug();
  ASSERT_TRUE(waitFor([&] { return device->connected(); }));
  EXPECT_EQ(device->reconnects(), 1u);
}

TEST_F(SpaceMouseDeviceTest, WithoutHotplugTheStatusSaysSo) {
  hotplug_->active = false;
  config_.rescanPeriodS = 1.0;
  auto device = makeDevice();
  EXPECT_FALSE(device->hotplugActive());
  EXPECT_EQ(device->hotplugStatus(), "fake hotplug off; looking for a SpaceMouse every 1 s");
}

TEST_F(SpaceMouseDeviceTest, HotplugSourceIsStoppedBeforeTheDeviceGoes) {
  auto device = makeDevice();
  ASSERT_TRUE(FakeHotplug::fire(*hotplug_));
  device.reset();
  EXPECT_FALSE(FakeHotplug::fire(*hotplug_));
}

TEST_F(SpaceMouseDeviceTest, HapticThreadCallsAllocateNothing) {
  auto device = makeDevice();
  queue({report(2, 100, 0, 0)});
  ASSERT_TRUE(waitFor([&] { return device->reportsParsed() >= 1; }));
  const test::AllocationCounter counter;
  double t = 0.0;
  for (int i = 0; i < 1000; ++i) {
    device->handlePose(t += 1e-3);
    device->handleVelocity(t);
    device->setFeedback(CouplingWrench{});
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(glm::length(device->handleVelocity(t).angularWorld), 0.0);
}

TEST_F(SpaceMouseDeviceTest, StallsDoNotFlingTheHandle) {
  auto device = makeDevice();
  queue({report(1, 350, 0, 0)});
  ASSERT_TRUE(waitFor([&] { return device->reportsParsed() >= 1; }));
  device->handlePose(0.0);
  EXPECT_NEAR(device->handlePose(10.0).position.x, 0.1 * SpaceMouseDevice::kMaxStepS, 1e-12);
}

TEST_F(SpaceMouseDeviceTest, LimitsAreThoseGiven) {
  DeviceLimits limits;
  limits.maxForceN = 3.0;
  SpaceMouseDevice device(Pose{}, limits, config_, std::make_unique<FakeTransport>(shared_));
  EXPECT_EQ(device.limits().maxForceN, 3.0);
}

}  // namespace
}  // namespace voxhap
