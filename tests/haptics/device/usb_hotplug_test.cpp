#include "haptics/device/usb_hotplug.h"

#include <atomic>
#include <cstdio>

#include <gtest/gtest.h>

#include "haptics/device/spacemouse_device.h"

namespace voxhap {
namespace {

std::vector<std::uint16_t> spaceMouseVendors() {
  return {kSpaceMouseVendorIds.begin(), kSpaceMouseVendorIds.end()};
}

TEST(UsbHotplugTest, NotStartedSaysSoAndDestructs) {
  const UsbHotplugWatcher watcher(spaceMouseVendors());
  EXPECT_EQ(watcher.state(), UsbHotplugWatcher::State::kNotStarted);
  EXPECT_FALSE(watcher.active());
  EXPECT_EQ(watcher.status(), "libusb hotplug not started");
}

TEST(UsbHotplugTest, StartsAndStopsCleanly) {
  std::atomic<int> arrivals{0};
  UsbHotplugWatcher::State state = UsbHotplugWatcher::State::kNotStarted;
  std::string status;
  // several times over: a thread or context outliving its watcher would show here (ASan)
  for (int i = 0; i < 3; ++i) {
    UsbHotplugWatcher watcher(spaceMouseVendors());
    watcher.start([&] { arrivals.fetch_add(1); });
    state = watcher.state();
    status = watcher.status();
    EXPECT_FALSE(status.empty());
    EXPECT_NE(state, UsbHotplugWatcher::State::kNotStarted);
    EXPECT_EQ(watcher.active(), state == UsbHotplugWatcher::State::kWatching);
    if (!watcher.active()) {
      EXPECT_EQ(status.rfind("libusb hotplug unavailable: ", 0), 0u) << status;
    } else {
      EXPECT_EQ(status, "libusb hotplug on for vendors 046d, 256f");
    }
  }
  if (state == UsbHotplugWatcher::State::kInitFailed) GTEST_SKIP() << status;
  RecordProperty("hotplugStatus", status);
  std::printf("%s\n", status.c_str());
}

}  // namespace
}  // namespace voxhap
